//! A glTF document checked, as JSON, before the `gltf` crate's own
//! validation and readers see it: the crate indexes, unwraps and asserts
//! on what it assumes valid, so a file that breaks an assumption would
//! panic there rather than be refused.
//!
//! One pass a concern, each returning the first problem as a
//! [`GltfError`] naming the object:
//! - [`refs`]: every index into another array is in range, every enum
//!   value is one the specification names;
//! - [`ranges`]: buffer views inside their buffers, accessors (and their
//!   strides) inside their views;
//! - [`uses`]: each accessor's component and element type is one the
//!   specification allows where it is used (a primitive's attribute or
//!   indices, an animation's input or output);
//! - [`graph`]: the node graph is a forest (one parent per node, no
//!   cycles, scenes list roots once);
//! - [`values`]: numbers the scene is built from (node transforms,
//!   cameras, lights, material factors) are finite and in range.

mod graph;
mod ranges;
mod refs;
mod uses;
mod values;

use super::Reader;
use crate::error::GltfError;
use gltf::json;

/// Checks `root` whole; `Ok` means the `gltf` crate's validation and
/// readers can run on it.
pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    refs::check(r, root)?;
    uses::check(r, root)?;
    ranges::check(r, root)?;
    graph::check(r, root)?;
    values::check(r, root)
}

/// `index` (found at `object`'s `field`) must be below `len`, the length
/// of the array `array` it indexes.
pub(super) fn in_range<T>(
    r: &Reader,
    object: &str,
    field: &str,
    index: &json::Index<T>,
    len: usize,
    array: &str,
) -> Result<(), GltfError> {
    let i = index.value();
    if i >= len {
        let has = match len {
            0 => format!("the file has no {array}"),
            n => format!("the file's {array} end at {array}[{}]", n - 1),
        };
        return Err(r.error(object, format!("{field} names {array}[{i}], but {has}")));
    }
    Ok(())
}

/// `checked` must hold a value the specification names.
pub(super) fn valid<'a, T>(
    r: &Reader,
    object: &str,
    field: &str,
    checked: &'a json::validation::Checked<T>,
) -> Result<&'a T, GltfError> {
    match checked {
        json::validation::Checked::Valid(v) => Ok(v),
        json::validation::Checked::Invalid => {
            Err(r.error(object, format!("{field} is not a value the glTF specification allows")))
        }
    }
}
