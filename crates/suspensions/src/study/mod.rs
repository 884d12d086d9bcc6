//! Design studies: many variants of one model, each a model file edited at JSON pointers, run and judged
//! alike ([`batch`]), cut into contiguous shards ([`shard`]) that the command's job arrays and Python's
//! workers each take one of.

pub mod batch;
pub mod shard;
