// The ldm method's splat (gi_ldm.h), fragment stage, after shaders/ldm_trace.glsl: the
// irradiance split photon v_slot gives the G-buffer's surface point p. The photon is a
// beam from its origin x1 along its direction: a disk of radius r on the origin's surface
// seen along the beam (semi-axes r and r |n1 . d|), each widening by `spread` per metre,
// neither below the width of a pixel at p.
// p receives when it lies inside the beam's ellipse at its distance s along it, not far
// beyond where the beam landed, faces the
// beam, and the first surface back along the beam lies in the origin's plane (within half
// a texel's diagonal, how far the texel's centre may be from p's ray): one trace back
// through the photon's own map, exact along that direction, so no light reaches a point
// behind a wall however thin. A trace that meets nothing (its texel's centre passes
// beside the scene) or meets a surface off the plane (the plane goes on where the
// origin's surface does not: a corner's block averages two surfaces) proves nothing, and
// the point gets nothing. Its irradiance is the flux through the ellipse times
// Silverman's kernel 3/pi (1 - l^2)^2 (a unit integral over the unit disk) over the
// ellipse's axes, times the receiver's cosine; additive blending sums the photons.
flat in int v_slot;

layout(std430, binding = 4) readonly buffer split_buffer { vec4 splits[]; };

uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform vec4 u_eye;              // the eye (w 1), or the direction towards it (w 0)
uniform float u_pixel_angle;     // a pixel's width over its distance (w 0: its width)

layout(location = 0) out vec4 out_irradiance;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pw = texelFetch(u_position, px, 0);
    if (pw.w == 0.0)
        discard;
    vec3 p = pw.xyz;
    vec3 n = normalize(texelFetch(u_normal, px, 0).xyz);
    vec4 a = splits[4 * v_slot], b = splits[4 * v_slot + 1], f = splits[4 * v_slot + 2],
         o = splits[4 * v_slot + 3];
    vec3 d = b.xyz, n1 = o.xyz;
    float receive = -dot(n, d);
    vec3 y = p - a.xyz;
    float s = dot(y, d);
    if (receive <= 0.01 || s <= 0.0) // a receiver along the beam (its normal's noise) gets none
        discard;
    vec3 e1 = cross(n1, d);
    e1 = dot(e1, e1) > 1e-12 ? normalize(e1) : normalize(cross(abs(d.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0), d));
    vec3 e2 = cross(d, e1);
    float c1 = abs(dot(n1, d));
    // No axis narrower than the pixel there: a thinner ellipse would put its whole flux
    // into the few pixels whose centres it happens to cover (hot pixels).
    float pixel = u_pixel_angle * (u_eye.w > 0.0 ? length(u_eye.xyz - p) : 1.0);
    float ra = max(b.w + f.w * s, pixel), rb = max(b.w * c1 + f.w * s, pixel);
    vec3 across = y - d * s;
    float u = dot(across, e1) / ra, v = dot(across, e2) / rb;
    float l2 = u * u + v * v;
    // The beam ends where it landed (a.w along its axis); off the axis it may reach a
    // surface tilted up to 60 degrees a little farther, as far as the splat's rectangle.
    if (l2 >= 1.0 || s > a.w + 2.0 * ra)
        discard;
    // Back along the beam from p (lifted off its surface): the first surface must lie in
    // the origin's plane, within the half diagonal of a texel that its centre may be away.
    int m = int(o.w);
    vec3 lifted = ldm_lift(p, n, receive);
    float back = ldm_trace(m, -sign(dot(d, ldm_direction(m))), lifted, 0.01 * ldm_texel());
    if (back < 0.0 || abs(dot(lifted - d * back - a.xyz, n1)) > 0.71 * ldm_texel())
        discard;
    float k = 3.0 / PI * (1.0 - l2) * (1.0 - l2);
    out_irradiance = vec4(f.rgb * (receive * k / (ra * rb)), 1.0);
}
