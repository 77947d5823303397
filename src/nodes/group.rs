//! A group node: one instance of a node group (a material function) defined in the
//! graph's `groups`. Its pins are the group's inputs and outputs, copied onto the
//! instance whenever the graph's groups are resolved (loading a file, editing a group),
//! so that every stage that reads a node's signature sees them.
//!
//! Groups are inlined before a graph is checked (see `graph::group::flatten`), so the
//! evaluation, range and emission parts below never meet a group node: the stages work
//! on the flattened nodes, which keep the path of groups they came from.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3};
use super::interval::Lanes;
use super::pins::Signature;
use super::ranges::Ranges;
use super::settings::{Basis, Setting};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather [$($units)*] [$($configured)* (Group, group)] $($rest)*);
    };
}
pub(super) use kinds;

/// An instance of the node group called `name`. Two instances are equal when they name
/// the same group: the pins are derived from the graph's definitions.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Group {
    /// The name of the group's definition in the graph.
    pub name: String,
    /// The group's pins, filled in when the graph's groups are resolved (not stored).
    #[serde(skip)]
    pub pins: Signature,
}

#[cfg(feature = "arbitrary")]
impl<'a> arbitrary::Arbitrary<'a> for Group {
    fn arbitrary(u: &mut arbitrary::Unstructured<'a>) -> arbitrary::Result<Group> {
        Ok(Group::named(String::arbitrary(u)?))
    }
}

impl PartialEq for Group {
    fn eq(&self, other: &Group) -> bool {
        self.name == other.name
    }
}

impl Group {
    /// An instance of group `name`, its pins not yet resolved.
    pub fn named(name: String) -> Group {
        Group {
            name,
            pins: Signature::default(),
        }
    }
}

/// Why a group node reached a stage that works on flattened graphs.
const FLATTENED: &str = "group nodes are inlined before a graph is checked";

impl Definition for Group {
    fn title(&self) -> &'static str {
        "Group"
    }
    fn category(&self) -> Category {
        Category::Group
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["node group", "function", "subgraph", "library"]
    }
    fn signature(&self) -> Signature {
        self.pins.clone()
    }
    fn reads_surface(&self) -> bool {
        true
    }
    fn basis(&self) -> Option<Basis> {
        None
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, _: &mut Emit) {
        unreachable!("{FLATTENED}")
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        unreachable!("{FLATTENED}")
    }
}

impl Evaluate for Group {
    fn eval<R: Real>(&self, _: &Eval<R>) -> Vec<V3<R>> {
        unreachable!("{FLATTENED}")
    }
}

impl Configure for Group {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        Vec::new()
    }
}

impl Catalogue for Group {
    /// Groups are offered from the graph's definitions and the library, not the menu
    /// of kinds.
    fn menu() -> Vec<(String, Self)> {
        Vec::new()
    }
    /// A group needs a definition, which the per-kind tests do not have.
    fn examples() -> Vec<Self> {
        Vec::new()
    }
}
