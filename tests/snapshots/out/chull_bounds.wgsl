// bounding_box program `chull_bounds`

fn rtp_chull_bounds(prim: u32, chull_bbmin: vec3<f32>, chull_bbmax: vec3<f32>) -> RtAabb {
    _ = prim;
    return RtAabb(chull_bbmin, chull_bbmax);
}
