//! Which suspension a model describes: a template, or the general form any suspension can be written in.
//! Every template expands into the general form ([`Template::expand`]), which the one builder builds.

use crate::description::double_wishbone::DoubleWishbone;
use crate::description::general::GeneralCorner;
use crate::description::layout::Layout;
use crate::description::macpherson::MacPherson;
use crate::description::twist_beam::TwistBeam;
use elastokin_core::Vec3;
use serde::{Deserialize, Serialize};

/// Which suspension a file describes: a template, or the general form any suspension can be written in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Template {
    /// A double-wishbone corner.
    DoubleWishbone(DoubleWishbone),
    /// A MacPherson strut corner.
    #[serde(rename = "macpherson")]
    MacPherson(MacPherson),
    /// A twist-beam axle, built whole.
    TwistBeam(TwistBeam),
    /// Any corner: bodies, joints, bushings, springs and the corner description (see
    /// [`crate::description::general`]).
    General(Box<GeneralCorner>),
}

impl Template {
    /// The key naming it in a model file: `macpherson`, `double_wishbone`, `twist_beam` or `general`.
    pub fn kind(&self) -> &'static str {
        match self {
            Template::DoubleWishbone(_) => "double_wishbone",
            Template::MacPherson(_) => "macpherson",
            Template::TwistBeam(_) => "twist_beam",
            Template::General(_) => "general",
        }
    }

    /// The suspension in the general form, which builds the same model: a template's expansion, or the
    /// general description itself.
    pub fn expand(&self) -> GeneralCorner {
        match self {
            Template::DoubleWishbone(t) => t.expand(),
            Template::MacPherson(t) => t.expand(),
            Template::TwistBeam(t) => t.expand(),
            Template::General(g) => (**g).clone(),
        }
    }

    /// Every hardpoint with its name in the model file, sorted by name.
    pub fn hardpoints(&self) -> Vec<(String, Vec3)> {
        let mut named: Vec<(String, Vec3)> = match self {
            Template::DoubleWishbone(t) => t.hardpoints.named().into_iter().map(|(n, p)| (n.to_string(), p)).collect(),
            Template::MacPherson(t) => t.hardpoints.named().into_iter().map(|(n, p)| (n.to_string(), p)).collect(),
            Template::TwistBeam(t) => t.hardpoints.named().into_iter().map(|(n, p)| (n.to_string(), p)).collect(),
            Template::General(g) => g.hardpoints.0.clone(),
        };
        named.sort_by(|a, b| a.0.cmp(&b.0));
        named
    }

    /// The name of the wheel-centre hardpoint.
    pub fn wheel_centre_name(&self) -> &str {
        match self {
            Template::General(g) => &g.corner.wheel_centre,
            _ => "wheel_centre",
        }
    }

    /// Where its parts are, by hardpoint name.
    pub(crate) fn layout(&self) -> Layout {
        match self {
            Template::DoubleWishbone(t) => t.layout(),
            Template::MacPherson(t) => t.layout(),
            Template::TwistBeam(t) => t.layout(),
            Template::General(g) => g.layout(),
        }
    }
}
