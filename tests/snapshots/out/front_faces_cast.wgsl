// any_hit program `front_faces_cast`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rtp_front_faces_cast(prd: ptr<function, Shadow>) {
    if ((rt_is_triangle_hit() && rt_is_triangle_hit_back_face()) && ((rt_ray_flags() & 8u) == 0u)) {
        rt_ignore_intersection();
    }
    (*prd).attenuation = vec3<f32>(0.0);
}
