//! The command's subcommands, one module each: its arguments (a clap `Args`) and its `run`; and what they
//! share: which analyses a command walks (`sweeps`), reading the inputs (`input`) and what `--strict`
//! refuses (`strict`). Writing the results is `crate::output`'s.

pub mod batch;
pub mod check;
pub mod compare;
pub mod expand;
pub mod import;
pub mod input;
pub mod live;
pub mod merge;
pub mod run;
pub mod sensitivity;
pub mod strict;
pub mod sweeps;
pub mod tolerance;
pub mod tune;
pub mod vehicle;

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// Every subcommand the command line knows is a module of its own here, named after it, and the code
    /// map (`ARCHITECTURE.md`) lists it: a subcommand added to `Command` without its module, or its module
    /// without its line in the map, fails here.
    #[test]
    fn every_subcommand_is_a_module_of_its_own_and_in_the_code_map() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let map = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
        let names: Vec<String> = crate::Cli::command().get_subcommands().map(|c| c.get_name().to_string()).collect();
        assert!(names.len() >= 11, "{names:?}");
        for name in &names {
            let file = format!("{}.rs", name.replace('-', "_"));
            assert!(root.join("src/command").join(&file).is_file(), "src/command/{file} for `elastokin {name}`");
            assert!(map.contains(&format!("`{file}`")), "ARCHITECTURE.md's code map lists src/command/{file}");
        }
    }
}
