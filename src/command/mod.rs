//! The command's subcommands, one module each: its arguments (a clap `Args`) and its `run`; and what they
//! share: which analyses a command walks (`sweeps`), reading the inputs (`input`) and what `--strict`
//! refuses (`strict`). Writing the results is `crate::output`'s.

pub mod batch;
pub mod check;
pub mod compare;
pub mod expand;
pub mod import;
pub mod input;
pub mod merge;
pub mod run;
pub mod sensitivity;
pub mod strict;
pub mod sweeps;
pub mod tolerance;
pub mod tune;
pub mod vehicle;
