// Screen-space ambient occlusion, horizon based (node/renderer_ao.h): the baseline the
// layered depth maps are measured against. Per pixel, SLICES planes through the view
// vector, each marched both ways on the screen over the projected distance limit (one
// step per pixel, at most STEPS a side) through the G-buffer's positions; each sample
// that rises above the horizon so far (from the normal's tangent plane up) hides the arc
// between, weighted by its distance's falloff (HBAO's incremental horizons); arcs are
// integrated with the cosine in closed form (Jimenez et al.'s ground-truth AO) and
// weighted by the normal's length in the slice. The sum is divided by the same sum with
// no occluder, so an open surface gets exactly 1. It sees only what the G-buffer holds:
// nothing off screen or behind the first surface.
in vec2 v_uv;

uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform vec4 u_eye;              // the eye (w 1), or the direction towards it (w 0)
uniform vec3 u_right;            // the view's axes in the world
uniform vec3 u_up;
uniform float u_pixel_angle;     // a pixel's width over its distance (w 0: its width)
uniform vec2 u_size;           // pixels

layout(location = 0) out vec4 out_ao;

const int SLICES = 8;
const int STEPS = 32;

// The cosine-weighted visible part of a slice from the view vector to angle h (signed:
// negative on the slice's other side), for a normal at angle g in the slice.
float arc(float h, float g)
{
    return 0.25 * (-cos(2.0 * h - g) + cos(g) + 2.0 * h * sin(g));
}

// One side of a slice (side +1 or -1 along the screen direction w): marching out from px,
// each sample above the horizon so far raises it, and the arc it hides counts as much as
// its surface hides at its distance (1 - ao_visibility(d)): all of it for occlusion
// within the limit, less the farther it is for obscurance (Bavoil et al.'s falloff).
// Returns the side's visible arc.
float side_visible(vec2 px, vec2 w, float side, vec3 p, vec3 v, float g, float stride,
                   int steps)
{
    float h = g + side * 0.5 * PI; // the open horizon: the normal's tangent plane
    float seen = arc(h, g);
    for (int k = 1; k <= steps; k++) {
        vec2 q = px + side * w * stride * float(k);
        if (any(lessThan(q, vec2(0.0))) || any(greaterThanEqual(q, u_size)))
            break;
        vec4 s = texelFetch(u_position, ivec2(q), 0);
        if (s.w == 0.0)
            continue;
        vec3 delta = s.xyz - p;
        float d = length(delta);
        if (d < 1e-5)
            continue;
        float a = side * acos(clamp(dot(delta, v) / d, -1.0, 1.0));
        if (side * (h - a) <= 0.0)
            continue; // not above the horizon so far
        seen -= (1.0 - ao_visibility(d)) * (arc(h, g) - arc(a, g));
        h = a;
    }
    return seen;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pw = texelFetch(u_position, px, 0);
    if (pw.w == 0.0) {
        out_ao = vec4(1.0);
        return;
    }
    vec3 p = pw.xyz;
    vec3 n = normalize(texelFetch(u_normal, px, 0).xyz);
    vec3 v = normalize(u_eye.xyz - p * u_eye.w);
    float dist = u_eye.w > 0.0 ? length(u_eye.xyz - p) : 1.0;
    float screen = max(u_size.x, u_size.y);
    float radius = u_ao_distance > 0.0 ? min(u_ao_distance / (dist * u_pixel_angle), screen) : screen;
    int steps = clamp(int(ceil(radius)), 1, STEPS);
    float stride = max(radius / float(steps), 1.0);
    float seen = 0.0, open = 0.0;
    for (int j = 0; j < SLICES; j++) {
        float phi = PI * (float(j) + 0.5) / float(SLICES);
        vec2 w = vec2(cos(phi), sin(phi));
        vec3 dir = u_right * w.x + u_up * w.y;
        vec3 t = dir - v * dot(dir, v);
        if (dot(t, t) < 1e-8)
            continue;
        t = normalize(t);
        vec3 axis = cross(v, t);
        vec3 np = n - axis * dot(n, axis);
        float len = length(np);
        if (len < 1e-4)
            continue;
        float g = atan(dot(np, t), dot(np, v));
        seen += len * (side_visible(gl_FragCoord.xy, w, 1.0, p, v, g, stride, steps) +
                       side_visible(gl_FragCoord.xy, w, -1.0, p, v, g, stride, steps));
        open += len * (arc(g - 0.5 * PI, g) + arc(g + 0.5 * PI, g));
    }
    out_ao = vec4(vec3(open > 0.0 ? clamp(seen / open, 0.0, 1.0) : 1.0), 1.0);
}
