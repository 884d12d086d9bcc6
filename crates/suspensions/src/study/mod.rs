//! Design studies: many variants of one model, each a model file edited at JSON pointers, run and judged
//! alike ([`batch`]); the command splits them into shards and Python spreads them over workers.

pub mod batch;
