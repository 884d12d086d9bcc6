//! Which analyses a command walks, over what range, in how many steps: the arguments `run`, `sensitivity`
//! and `compare` share, an analysis by its command-line name, and the readers of steps and ranges.

use crate::output::Failure;
use clap::{Args, ValueEnum};
use elastokin::solver::LoadPath;
use elastokin::suspensions::kc::{self, Analysis, Settings};

/// The most load steps a sweep may take (the suite's limit, which its advice on steps respects).
pub use elastokin::solver::MAX_STEPS;

/// Which analyses a command walks, over what range, in how many steps: `run`'s and `sensitivity`'s.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// One analysis instead of all of them (--help lists each one's load parameter, units and default range)
    #[arg(long, value_enum, value_name = "NAME")]
    pub analysis: Option<AnalysisName>,
    /// The load parameter's range, in the analysis's own units (needs --analysis)
    #[arg(long, value_name = "FROM,TO", value_parser = parse_range, allow_hyphen_values = true)]
    pub range: Option<(f64, f64)>,
    #[command(flatten)]
    pub load: LoadSteps,
}

/// How many load steps each sweep takes: `--steps`, shared by the commands that walk the suite.
#[derive(Debug, Args)]
pub struct LoadSteps {
    #[arg(
        long,
        value_name = "N",
        default_value_t = 32,
        value_parser = parse_steps,
        allow_negative_numbers = true,
        help = format!("Load steps per sweep, 1 to {MAX_STEPS}")
    )]
    pub steps: usize,
}

impl SweepArgs {
    /// The analyses asked for by name (none: the suite).
    pub fn which(&self) -> Vec<Analysis> {
        self.analysis.map(|a| vec![a.analysis()]).unwrap_or_default()
    }

    /// Refuses a range without an analysis to give it units, and settings an analysis cannot take, as bad
    /// input before anything runs.
    pub fn check(&self, settings: &Settings) -> Result<(), Failure> {
        if self.range.is_some() && self.analysis.is_none() {
            return Err(Failure::Input(
                "--range needs --analysis NAME: each analysis has its own load parameter and units".into(),
            ));
        }
        check_each(&self.which(), settings)
    }
}

/// Refuses `settings` that an analysis of `which` (the suite when empty) cannot take, as bad input before
/// anything runs.
pub fn check_each(which: &[Analysis], settings: &Settings) -> Result<(), Failure> {
    for &a in if which.is_empty() { &kc::ALL[..] } else { which } {
        kc::check_settings(a, settings).map_err(|e| Failure::Input(e.to_string()))?;
    }
    Ok(())
}

/// An analysis by its command-line name. Its help (what its load parameter is, and its default range) is
/// the library's declaration of it (`Analysis::parameter`, `Analysis::default_range`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AnalysisName(Analysis);

/// Every analysis, as the command lists them.
static ANALYSIS_NAMES: std::sync::LazyLock<Vec<AnalysisName>> =
    std::sync::LazyLock::new(|| kc::ALL.iter().map(|&a| AnalysisName(a)).collect());

impl ValueEnum for AnalysisName {
    fn value_variants<'a>() -> &'a [Self] {
        &ANALYSIS_NAMES
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let a = self.0;
        let help = match a.rig_words() {
            Some(rig) => format!("{}, {rig}; {}", a.parameter(), a.default_range()),
            None => format!("{}; {}", a.parameter(), a.default_range()),
        };
        Some(clap::builder::PossibleValue::new(self.0.name()).help(help))
    }
}

impl AnalysisName {
    /// The analysis of this name.
    pub fn analysis(self) -> Analysis {
        self.0
    }
}

/// A number of load steps, 1 to [`MAX_STEPS`].
pub fn parse_steps(text: &str) -> Result<usize, String> {
    let n: u64 = text.trim().parse().map_err(|_| format!("'{text}' is not a whole number of steps"))?;
    let n = usize::try_from(n).unwrap_or(usize::MAX);
    LoadPath::check_steps(n).map(|()| n).map_err(|e| e.to_string())
}

fn parse_range(text: &str) -> Result<(f64, f64), String> {
    let (from, to) = text.split_once(',').ok_or("give FROM,TO, e.g. --range -0.02,0.02")?;
    let parse = |s: &str| match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{}' is not a finite number", s.trim())),
    };
    let (from, to) = (parse(from)?, parse(to)?);
    if from == to {
        return Err("FROM and TO must differ".into());
    }
    if !(to - from).is_finite() {
        return Err("FROM and TO are too far apart to step between".into());
    }
    Ok((from, to))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_analysis_has_its_command_line_name() {
        let names: Vec<AnalysisName> = AnalysisName::value_variants().to_vec();
        assert_eq!(names.len(), kc::ALL.len());
        for (name, analysis) in names.into_iter().zip(kc::ALL) {
            assert_eq!(name.analysis(), analysis);
        }
    }
}
