// The ldm method's photon split (gi_ldm.h), after shaders/ldm_trace.glsl: one invocation
// per primary photon and map. The photon leaves its surface along the map's direction on
// its normal's side (each map gives exactly one direction of its hemisphere), is traced
// through the map to the first surface, and is written to its own slot, photon * maps +
// map, so the buffer's layout never depends on the GPU's order: origin and travel, the
// direction and the footprint's radius, the flux it carries (the primary's, times
// |n . d| over the sum of |n . d| over all maps, so the split flux adds up to the
// primary's exactly; times the medium's transmittance over its way) and the spread, the
// origin's normal and the map. A photon that leaves the scene or travels beyond
// u_max_distance leaves a slot of zero flux.
layout(local_size_x = 64) in;

layout(std430, binding = 3) readonly buffer photon_buffer { vec4 photons[]; };  // 3 per photon
layout(std430, binding = 4) writeonly buffer split_buffer { vec4 splits[]; };   // 4 per slot

uniform int u_photon_count;
uniform float u_max_distance;
uniform float u_absorption;

void main()
{
    int slot = int(gl_GlobalInvocationID.x);
    if (slot >= u_photon_count * u_ldm_count)
        return;
    int i = slot / u_ldm_count, m = slot % u_ldm_count;
    vec4 pr = photons[3 * i], nw = photons[3 * i + 1], fs = photons[3 * i + 2];
    vec3 d = ldm_direction(m);
    float c = dot(nw.xyz, d);
    float t = c != 0.0 ? ldm_trace_from(m, sign(c), pr.xyz, nw.xyz) : -1.0;
    if (t <= 0.0 || (u_max_distance > 0.0 && t > u_max_distance)) {
        for (int k = 0; k < 4; k++)
            splits[4 * slot + k] = vec4(0.0);
        return;
    }
    splits[4 * slot] = vec4(pr.xyz, t);
    splits[4 * slot + 1] = vec4(sign(c) * d, pr.w);
    splits[4 * slot + 2] = vec4(fs.rgb * (abs(c) * nw.w * transmittance(u_absorption, t)), fs.w);
    splits[4 * slot + 3] = vec4(nw.xyz, float(m));
}
