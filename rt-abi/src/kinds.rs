//! Program kinds: the `#[rt_program(kind)]` spellings and what each kind
//! may take and call.

/// The nine kinds of ray program, as in OptiX, written
/// `#[rt_program(kind)]` (rt-std calls it `ProgramKind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Entry point, run once per launch index.
    RayGeneration,
    /// Called when an exception is raised.
    Exception,
    /// Called for the closest committed intersection.
    ClosestHit,
    /// Called for every potential closest intersection.
    AnyHit,
    /// Called when a ray hits nothing.
    Miss,
    /// Intersects a ray with one custom primitive.
    Intersection,
    /// Computes the bounds of one custom primitive.
    BoundingBox,
    /// Chooses which child of a selector a ray enters.
    Visit,
    /// A function called through an id held in a value (OptiX bindless
    /// callable programs, OptiX 7 direct callables).
    Callable,
}

use Kind::*;

/// Every kind, in OptiX's order.
pub const ALL_KINDS: [Kind; 9] =
    [RayGeneration, Exception, ClosestHit, AnyHit, Miss, Intersection, BoundingBox, Visit, Callable];

impl Kind {
    /// The `#[rt_program(...)]` spelling.
    pub const fn name(self) -> &'static str {
        match self {
            RayGeneration => "ray_generation",
            Exception => "exception",
            ClosestHit => "closest_hit",
            AnyHit => "any_hit",
            Miss => "miss",
            Intersection => "intersection",
            BoundingBox => "bounding_box",
            Visit => "visit",
            Callable => "callable",
        }
    }

    /// The `rt_std::program::ProgramKind` variant name.
    pub fn variant(self) -> &'static str {
        match self {
            RayGeneration => "RayGeneration",
            Exception => "Exception",
            ClosestHit => "ClosestHit",
            AnyHit => "AnyHit",
            Miss => "Miss",
            Intersection => "Intersection",
            BoundingBox => "BoundingBox",
            Visit => "Visit",
            Callable => "Callable",
        }
    }

    /// "a miss program", "an any_hit program": for messages.
    pub fn a_program(self) -> String {
        let article = if matches!(self, Exception | AnyHit | Intersection) { "an" } else { "a" };
        format!("{article} {} program", self.name())
    }

    pub fn from_name(name: &str) -> Option<Kind> {
        ALL_KINDS.into_iter().find(|k| k.name() == name)
    }

    /// The parameters a program of this kind may take besides `#[var]`s.
    pub fn signature_help(self) -> &'static str {
        match self {
            RayGeneration | Exception => "only `#[var]` parameters",
            ClosestHit | AnyHit => "`prd: &mut Payload`, `attr: &Attributes` and `#[var]` parameters",
            Miss => "`prd: &mut Payload` and `#[var]` parameters",
            Intersection => "`prim: u32`, `attr: &mut Attributes` and `#[var]` parameters",
            BoundingBox => "`prim: u32` and `#[var]` parameters, returning `Aabb`",
            Visit => "`prd: &Payload` and `#[var]` parameters, returning the child index as `u32`",
            Callable => "arguments by value of the subset's types, returning a value or nothing",
        }
    }
}

/// Which kinds may call an intrinsic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Callers {
    All,
    Only(&'static [Kind]),
}

impl Callers {
    pub fn allows(self, kind: Kind) -> bool {
        match self {
            Callers::All => true,
            Callers::Only(kinds) => kinds.contains(&kind),
        }
    }

    /// The list as rt-std's docs spell it: `Program kinds: a, b.`
    pub fn doc_line(self) -> String {
        match self {
            Callers::All => "Program kinds: all.".into(),
            Callers::Only(k) => {
                format!("Program kinds: {}.", k.iter().map(|k| k.name()).collect::<Vec<_>>().join(", "))
            }
        }
    }
}
