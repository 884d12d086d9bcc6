//! Design: how the figures move with the numbers of a model file. A parameter is any number of a model
//! file, named by the JSON pointer `elastokin batch` edits ([`parameter`]); its sensitivities are the exact
//! derivatives of an analysis's rows and figures through the equilibrium ([`sensitivity`]). On them:
//! tuning to targets ([`targets`], [`tune`]) and tolerance stack-up ([`tolerance`]).

pub mod fit;
pub mod judge;
mod keys;
pub mod live;
pub mod parameter;
pub mod sensitivity;
pub mod targets;
pub mod tolerance;
pub mod tune;

pub use keys::KeyRefusal;
pub use parameter::{
    hardpoint_pointers, parameter_value_words, parameter_words, rate_pointers, NoNumber, ParameterError, Parameters,
};
pub use sensitivity::{
    analysis_sensitivity, suite_sensitivity, AnalysisSensitivity, Derivative, NoDerivative, Rate, SensitivityError,
    SuiteSensitivity,
};
