// Importance of every RSM texel as a VAL, two channels (val_select.h): the view term over
// the head's view samples times the flux, and the flux. Written column by column, (layer,
// x) a column of rows y, for the summed-area tables.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 4) writeonly buffer Sums { vec2 sums[]; };
layout(std430, binding = 6) readonly buffer Samples { vec4 samples[]; }; // point, normal

uniform int u_samples;

void main()
{
    ivec3 t = ivec3(gl_GlobalInvocationID.xy, gl_WorkGroupID.z);
    if (t.x >= u_rsm_size || t.y >= u_rsm_size)
        return;
    val v = val_fetch(t);
    float phi = v.flux.r + v.flux.g + v.flux.b;
    vec2 q = vec2(0.0);
    if (phi > 0.0) {
        float sum = 0.0;
        for (int s = 0; s < u_samples; s++) {
            vec3 x = samples[2 * s].xyz, nx = samples[2 * s + 1].xyz;
            vec3 d = x - v.position;
            float r2 = dot(d, d);
            if (!(r2 > 0.0))
                continue;
            float cos_l = dot(v.normal, d), cos_s = -dot(nx, d); // times r
            if (cos_l > 0.0 && cos_s > 0.0)
                sum += cos_l * cos_s / (r2 * (v.area + PI * r2));
        }
        q = vec2(phi * (u_samples > 0 ? sum / float(u_samples) : 0.0), phi);
    }
    sums[(t.z * u_rsm_size + t.x) * u_rsm_size + t.y] = q;
}
