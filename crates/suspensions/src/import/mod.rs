//! Other programs' suspension files read into descriptions: each importer turns a foreign file into the
//! general form ([`crate::description::GeneralCorner`]), with a note for every value read, taken another
//! way or left out. Importers know descriptions and the file format's errors, nothing built; the
//! `document` layer above builds what they read.

pub mod chrono;
