// The presentation pass (node/present/present_warp.c, common/warp/warp_map.h): the rendered image
// warped onto the projector image and blended (MPCDI 2.4, in linear light:
// P = Pi alpha (1 - beta) + beta), or, showing the blend regions, the pattern tinted by
// its weight where this projector is dimmed.
in vec2 v_uv;
in float v_weight;

uniform int u_mode;            // WARP_NONE, WARP_UV_GRID, WARP_POINT_GRID, WARP_MESH
uniform vec4 u_rect;           // the projector image in the framebuffer: x, y, w, h pixels
uniform sampler2D u_source;    // the rendered image, its top row first
uniform sampler2D u_grid;      // grid samples, bottom row first (texelFetch)
uniform mat4 u_cave_to_clip;   // WARP_POINT_GRID: surface point to the image's clip space
uniform sampler2D u_alpha;     // blend maps over the projector image, top row first
uniform sampler2D u_beta;
uniform int u_alpha_map, u_beta_map;
uniform float u_alpha_gamma;
uniform float u_display_gamma;
uniform int u_show_blend;

layout(location = 0) out vec4 out_color;

const float UNKNOWN = -1e29; // warp_map.h: WARP_UNKNOWN is below

// The grid at projector point pos: sample (i, j) at its cell's centre, linear between
// centres and beyond the outer ones.
vec3 grid_at(vec2 pos, out bool known)
{
    ivec2 n = textureSize(u_grid, 0);
    vec2 g = pos * vec2(n) - 0.5;
    ivec2 i = clamp(ivec2(floor(g)), ivec2(0), n - 2);
    vec2 f = g - vec2(i);
    vec3 a = texelFetch(u_grid, i, 0).rgb, b = texelFetch(u_grid, i + ivec2(1, 0), 0).rgb;
    vec3 c = texelFetch(u_grid, i + ivec2(0, 1), 0).rgb, d = texelFetch(u_grid, i + ivec2(1, 1), 0).rgb;
    known = min(min(a.x, b.x), min(c.x, d.x)) > UNKNOWN;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

void main()
{
    vec2 pixel = gl_FragCoord.xy - u_rect.xy;
    vec2 pos = pixel / u_rect.zw;
    vec2 uv = pos;
    bool known = true;
    if (u_mode == 1) {
        uv = grid_at(pos, known).xy;
    } else if (u_mode == 2) {
        vec4 clip = u_cave_to_clip * vec4(grid_at(pos, known), 1.0);
        known = known && clip.w > 0.0;
        uv = clip.xy / clip.w * 0.5 + 0.5;
    } else if (u_mode == 3) {
        uv = v_uv;
    }
    vec3 c = vec3(0.0);
    ivec2 size = textureSize(u_source, 0);
    if (u_mode == 0 && ivec2(u_rect.zw) == size)
        c = texelFetch(u_source, ivec2(int(pixel.x), size.y - 1 - int(pixel.y)), 0).rgb; // 1:1, exact
    else if (known && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))))
        c = texture(u_source, vec2(uv.x, 1.0 - uv.y)).rgb;
    vec3 alpha = vec3(u_mode == 3 ? v_weight : 1.0), beta = vec3(0.0);
    vec2 map = vec2(pos.x, 1.0 - pos.y);
    if (u_alpha_map != 0)
        alpha *= pow(texture(u_alpha, map).rgb, vec3(u_alpha_gamma));
    if (u_beta_map != 0)
        beta = texture(u_beta, map).rgb;
    float weight = min(alpha.r, min(alpha.g, alpha.b));
    if (u_show_blend != 0) {
        // Where this projector is dimmed: red where it gives little, green where nearly all,
        // dark blue where it gives nothing; the pattern stays readable underneath.
        if (weight < 0.999) {
            vec3 tint = weight <= 0.0 ? vec3(0.0, 0.0, 0.35) : mix(vec3(1.0, 0.15, 0.1), vec3(0.1, 0.9, 0.2), weight);
            c = mix(c, tint, 0.6);
        }
    } else if (u_alpha_map != 0 || u_beta_map != 0 || u_mode == 3) {
        vec3 light = pow(c, vec3(u_display_gamma)) * alpha * (1.0 - beta) + beta;
        c = pow(light, vec3(1.0 / u_display_gamma));
    }
    out_color = vec4(c, 1.0);
}
