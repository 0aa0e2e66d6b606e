//! Byte ranges: each accessor's count at least 1, each buffer view inside its buffer's declared length, each
//! view's stride one the specification allows, each accessor's elements
//! (with the view's stride) inside its view. Buffers' data is checked
//! against their declared lengths when it is read, so what passes here
//! lies inside the bytes the readers get.

use crate::error::GltfError;
use crate::gltf::Reader;
use gltf::json;

pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    for (i, view) in root.buffer_views.iter().enumerate() {
        let object = format!("bufferViews[{i}]");
        let buffer = &root.buffers[view.buffer.value()];
        let offset = view.byte_offset.map_or(0, |o| o.0);
        let end = offset.checked_add(view.byte_length.0);
        if end.is_none_or(|end| end > buffer.byte_length.0) {
            return Err(r.error(
                &object,
                format!(
                    "spans bytes {offset}..{} of buffers[{}], which declares {}",
                    end.map_or("(overflow)".to_string(), |e| e.to_string()),
                    view.buffer.value(),
                    buffer.byte_length.0
                ),
            ));
        }
        if let Some(stride) = &view.byte_stride
            && !(4..=252).contains(&stride.0)
        {
            return Err(r.error(&object, format!("byteStride {} is outside 4..=252", stride.0)));
        }
    }
    for (i, a) in root.accessors.iter().enumerate() {
        let object = format!("accessors[{i}]");
        // The `gltf` crate's readers compute `count - 1`.
        if a.count.0 == 0 || a.sparse.as_ref().is_some_and(|s| s.count.0 == 0) {
            return Err(r.error(&object, "has a count of 0 (the specification asks for at least 1)".into()));
        }
        let Some(view_index) = &a.buffer_view else { continue };
        let view = &root.buffer_views[view_index.value()];
        // Both checked valid by `refs`.
        let (json::validation::Checked::Valid(c), json::validation::Checked::Valid(t)) = (&a.component_type, &a.type_)
        else {
            continue;
        };
        let size = (c.0.size() * t.multiplicity()) as u64;
        let stride = view.byte_stride.as_ref().map_or(size, |s| s.0 as u64);
        if stride < size {
            return Err(r.error(
                &object,
                format!(
                    "its elements are {size} bytes, but bufferViews[{}] has byteStride {stride}",
                    view_index.value()
                ),
            ));
        }
        let offset = a.byte_offset.map_or(0, |o| o.0);
        let count = a.count.0;
        let needed =
            (count - 1).checked_mul(stride).and_then(|n| n.checked_add(size)).and_then(|n| n.checked_add(offset));
        if needed.is_none_or(|n| n > view.byte_length.0) {
            return Err(r.error(
                &object,
                format!(
                    "{count} elements of {size} bytes (stride {stride}) from offset {offset} do not fit bufferViews[{}] ({} bytes)",
                    view_index.value(),
                    view.byte_length.0
                ),
            ));
        }
    }
    Ok(())
}
