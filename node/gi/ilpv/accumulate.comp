// dst = a * dst + b * src per colour texture, for the ILPV's history scale and result
// (ilpv.h) and the classic LPV's sum (lpv_classic.h). a = 0 does not read dst (it may hold
// anything, a stale history), b = 0 does not read src.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba32f, binding = 0) uniform image3D u_dst_r;
layout(rgba32f, binding = 1) uniform image3D u_dst_g;
layout(rgba32f, binding = 2) uniform image3D u_dst_b;
uniform sampler3D u_src_r;
uniform sampler3D u_src_g;
uniform sampler3D u_src_b;

uniform ivec3 u_size;
uniform float u_a;
uniform float u_b;

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_size)))
        return;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    if (u_a != 0.0) {
        r = u_a * imageLoad(u_dst_r, c);
        g = u_a * imageLoad(u_dst_g, c);
        b = u_a * imageLoad(u_dst_b, c);
    }
    if (u_b != 0.0) {
        r += u_b * texelFetch(u_src_r, c, 0);
        g += u_b * texelFetch(u_src_g, c, 0);
        b += u_b * texelFetch(u_src_b, c, 0);
    }
    imageStore(u_dst_r, c, r);
    imageStore(u_dst_g, c, g);
    imageStore(u_dst_b, c, b);
}
