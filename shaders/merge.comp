// ILPV merge (paper eq. 3.4): L = a * history + b * injected, per colour texture.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba32f, binding = 0) uniform readonly image3D u_history_r;
layout(rgba32f, binding = 1) uniform readonly image3D u_history_g;
layout(rgba32f, binding = 2) uniform readonly image3D u_history_b;
layout(rgba32f, binding = 3) uniform readonly image3D u_injected_r;
layout(rgba32f, binding = 4) uniform readonly image3D u_injected_g;
layout(rgba32f, binding = 5) uniform readonly image3D u_injected_b;
layout(rgba32f, binding = 6) uniform writeonly image3D u_dst_r;
layout(rgba32f, binding = 7) uniform writeonly image3D u_dst_g;
layout(rgba32f, binding = 8) uniform writeonly image3D u_dst_b;

uniform ivec3 u_size;
uniform float u_a;
uniform float u_b;

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_size)))
        return;
    vec4 r = u_b * imageLoad(u_injected_r, c);
    vec4 g = u_b * imageLoad(u_injected_g, c);
    vec4 b = u_b * imageLoad(u_injected_b, c);
    // a == 0 on the first frame: the history may hold anything, do not even read it.
    if (u_a != 0.0) {
        r += u_a * imageLoad(u_history_r, c);
        g += u_a * imageLoad(u_history_g, c);
        b += u_a * imageLoad(u_history_b, c);
    }
    imageStore(u_dst_r, c, r);
    imageStore(u_dst_g, c, g);
    imageStore(u_dst_b, c, b);
}
