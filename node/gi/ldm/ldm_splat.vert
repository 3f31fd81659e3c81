// The ldm method's splat (gi_ldm.h), vertex stage: vertices 6k..6k+5 are split photon k's,
// a screen rectangle around where it landed, covering a sphere of twice its
// footprint's larger radius there (a receiver tilted up to 60 degrees from the beam), the
// whole screen when the sphere reaches the eye's plane, nothing when it lies behind it.
// An empty slot is drawn off screen.
layout(std430, binding = 4) readonly buffer split_buffer { vec4 splits[]; };

uniform mat4 u_view_projection;
uniform vec2 u_scale;            // the projection's x and y scale (clip per view unit)
uniform int u_perspective;       // 0: orthographic (w is 1)
uniform vec2 u_pixel;            // a pixel's size in clip units

flat out int v_slot;

void main()
{
    int slot = gl_VertexID / 6;
    v_slot = slot;
    vec4 a = splits[4 * slot], b = splits[4 * slot + 1], f = splits[4 * slot + 2];
    const vec2 corner[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1),
                                   vec2(1, 1), vec2(-1, 1));
    vec3 landed = a.xyz + b.xyz * a.w;
    float reach = 2.0 * (b.w + f.w * a.w);
    vec4 c = u_view_projection * vec4(landed, 1.0);
    if (f.r + f.g + f.b <= 0.0 || (u_perspective != 0 && c.w < -reach)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    vec2 centre = vec2(0.0), half_size = vec2(1.0);
    if (u_perspective == 0 || c.w > reach) {
        centre = c.xy / c.w;
        half_size = max(reach * u_scale / c.w, u_pixel); // at least a pixel: the
        // fragment stage widens a beam narrower than that to a pixel
    }
    gl_Position = vec4(centre + corner[gl_VertexID % 6] * half_size, 0.0, 1.0);
}
