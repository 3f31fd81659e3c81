// FXAA, after Lottes' FXAA 3.11 "quality" algorithm (NVIDIA white paper, 2009/2011), on
// the tone-mapped 8-bit image: find a pixel's edge from the luma of its 3x3 neighbourhood,
// walk along the edge to both of its ends, and shift the sample across the edge by how far
// the pixel lies from the nearer end; a sub-pixel term blends single-pixel features.
// A pixel whose neighbourhood's luma range is below the thresholds is copied unchanged.
uniform sampler2D u_ldr;   // linear filtering: the shifted samples blend two pixels
uniform vec2 u_texel;      // 1 / size

layout(location = 0) out vec4 out_color;

// Lottes' "quality" defaults: edges from a contrast of 1/8 of the local maximum, none
// below 1/16 (dark noise); sub-pixel blending 3/4.
const float EDGE_THRESHOLD = 0.125;
const float EDGE_THRESHOLD_MIN = 0.0625;
const float SUBPIXEL = 0.75;
// Step lengths of the walk along the edge (his preset 12: 12 steps, longer far out).
const int STEPS = 12;
const float STEP[12] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
float luma_at(ivec2 p)
{
    ivec2 last = textureSize(u_ldr, 0) - 1;
    return luma(texelFetch(u_ldr, clamp(p, ivec2(0), last), 0).rgb);
}
float luma_uv(vec2 uv) { return luma(textureLod(u_ldr, uv, 0.0).rgb); }

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 centre = texelFetch(u_ldr, p, 0);
    float m = luma(centre.rgb);
    float n = luma_at(p + ivec2(0, 1)), s = luma_at(p + ivec2(0, -1));
    float e = luma_at(p + ivec2(1, 0)), w = luma_at(p + ivec2(-1, 0));
    float lo = min(m, min(min(n, s), min(e, w)));
    float hi = max(m, max(max(n, s), max(e, w)));
    float range = hi - lo;
    if (range < max(EDGE_THRESHOLD_MIN, hi * EDGE_THRESHOLD)) {
        out_color = centre;
        return;
    }
    float nw = luma_at(p + ivec2(-1, 1)), ne = luma_at(p + ivec2(1, 1));
    float sw = luma_at(p + ivec2(-1, -1)), se = luma_at(p + ivec2(1, -1));

    // A horizontal edge changes along y: the second differences across rows.
    float horizontal = abs(nw + sw - 2.0 * w) + 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e);
    float vertical = abs(nw + ne - 2.0 * n) + 2.0 * abs(w + e - 2.0 * m) + abs(sw + se - 2.0 * s);
    bool is_horizontal = horizontal >= vertical;

    // The side of the pixel the edge lies on: the steeper of the two neighbours across it.
    float l1 = is_horizontal ? s : w, l2 = is_horizontal ? n : e;
    float g1 = l1 - m, g2 = l2 - m;
    bool first_steeper = abs(g1) >= abs(g2);
    float gradient = 0.25 * max(abs(g1), abs(g2));
    float across = is_horizontal ? u_texel.y : u_texel.x;
    float edge_luma;
    if (first_steeper) {
        across = -across;
        edge_luma = 0.5 * (l1 + m);
    } else {
        edge_luma = 0.5 * (l2 + m);
    }

    // Walk along the edge, half a pixel across it, until its luma leaves edge_luma.
    vec2 uv = (vec2(p) + 0.5) * u_texel;
    if (is_horizontal)
        uv.y += 0.5 * across;
    else
        uv.x += 0.5 * across;
    vec2 along = is_horizontal ? vec2(u_texel.x, 0.0) : vec2(0.0, u_texel.y);
    vec2 uv1 = uv - along, uv2 = uv + along;
    float end1 = luma_uv(uv1) - edge_luma, end2 = luma_uv(uv2) - edge_luma;
    bool done1 = abs(end1) >= gradient, done2 = abs(end2) >= gradient;
    for (int i = 1; i < STEPS && !(done1 && done2); i++) {
        if (!done1) {
            uv1 -= along * STEP[i];
            end1 = luma_uv(uv1) - edge_luma;
            done1 = abs(end1) >= gradient;
        }
        if (!done2) {
            uv2 += along * STEP[i];
            end2 = luma_uv(uv2) - edge_luma;
            done2 = abs(end2) >= gradient;
        }
    }
    float d1 = is_horizontal ? uv.x - uv1.x : uv.y - uv1.y;
    float d2 = is_horizontal ? uv2.x - uv.x : uv2.y - uv.y;
    bool nearer1 = d1 < d2;
    float offset = 0.5 - min(d1, d2) / (d1 + d2);
    // Only when the nearer end's luma varies the way the centre's does: the pixel is on
    // the side of the edge the walk found.
    bool centre_below = m < edge_luma;
    if (((nearer1 ? end1 : end2) < 0.0) == centre_below)
        offset = 0.0;

    // Sub-pixel: how much the centre differs from its neighbourhood's low-pass.
    float average = (2.0 * (n + s + e + w) + nw + ne + sw + se) / 12.0;
    float sub = clamp(abs(average - m) / range, 0.0, 1.0);
    sub = (-2.0 * sub + 3.0) * sub * sub;
    offset = max(offset, sub * sub * SUBPIXEL);

    vec2 shifted = (vec2(p) + 0.5) * u_texel;
    if (is_horizontal)
        shifted.y += offset * across;
    else
        shifted.x += offset * across;
    out_color = vec4(textureLod(u_ldr, shifted, 0.0).rgb, centre.a);
}
