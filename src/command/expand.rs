//! `elastokin expand MODEL`: the model file with its suspension in the general form, which builds the same
//! model.

use super::check::CheckArgs;
use super::input::read_model;
use super::strict::strict_model;
use crate::output::{Failure, Stdout};
use elastokin::suspensions::{SuspensionFile, Template};

/// `expand`: the model file with its suspension in the general form, which builds the same model.
pub fn run(args: CheckArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let file = read_model(&args.model)?.file;
    strict_model(&args.model, &file, strict)?;
    let general = SuspensionFile { suspension: Template::General(Box::new(file.suspension.expand())), ..file };
    out.line(general.to_json())?;
    Ok(())
}
