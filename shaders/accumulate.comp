// Classic LPV accumulation (lpv_classic.h): accum = (first ? 0 : accum) + weight * step,
// per colour texture. weight is 1, or 0 to clear the sum when a frame has no steps.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba32f, binding = 0) uniform image3D u_accum_r;
layout(rgba32f, binding = 1) uniform image3D u_accum_g;
layout(rgba32f, binding = 2) uniform image3D u_accum_b;
layout(rgba32f, binding = 3) uniform readonly image3D u_step_r;
layout(rgba32f, binding = 4) uniform readonly image3D u_step_g;
layout(rgba32f, binding = 5) uniform readonly image3D u_step_b;

uniform ivec3 u_size;
uniform int u_first;
uniform float u_weight;

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_size)))
        return;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    if (u_first == 0) {
        r = imageLoad(u_accum_r, c);
        g = imageLoad(u_accum_g, c);
        b = imageLoad(u_accum_b, c);
    }
    imageStore(u_accum_r, c, r + u_weight * imageLoad(u_step_r, c));
    imageStore(u_accum_g, c, g + u_weight * imageLoad(u_step_g, c));
    imageStore(u_accum_b, c, b + u_weight * imageLoad(u_step_b, c));
}
