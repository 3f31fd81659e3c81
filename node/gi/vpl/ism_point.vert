// One point of a VPL's subset into its imperfect shadow map (node/vpl_ism.c): vertex k
// belongs to VPL k / u_points; the paraboloid map of that VPL's hemisphere is its tile of
// the atlas. Out: the point's distance / far (depth), its exact position in level-0 texels
// and its disk's radius in texels (the pull-push record, shaders/ism_pull.frag).
layout(location = 0) in vec3 in_position;

uniform sampler2D u_vpls;     // as in shade.frag: (0, i) position, (1, i) normal
uniform int u_points;         // points per VPL
uniform int u_size;           // texels per tile side
uniform int u_tiles;          // tiles per atlas side
uniform float u_far;
uniform float u_radius;       // world radius of each point's disk
uniform int u_splat;          // 1: a disk of that radius, else one texel

flat out vec4 v_point;        // distance / far, x, y (texels), radius (texels)
flat out vec4 v_tile;         // the tile's texel rectangle: x0, y0, x1, y1

void main()
{
    int i = gl_VertexID / u_points;
    vec3 y = texelFetch(u_vpls, ivec2(0, i), 0).xyz;
    vec3 n = texelFetch(u_vpls, ivec2(1, i), 0).xyz;
    vec3 d = in_position - y;
    float l = length(d);
    vec3 m = ism_project(n, d);
    float size = float(u_size), atlas = size * float(u_tiles);
    vec2 origin = vec2(i % u_tiles, i / u_tiles) * size;
    vec2 texel = origin + (m.xy * 0.5 + 0.5) * size;
    float radius = u_radius / (l * (1.0 + m.z)) * 0.5 * size;
    v_point = vec4(l / u_far, texel, radius);
    v_tile = vec4(origin, origin + size);
    gl_PointSize = u_splat != 0 ? clamp(2.0 * radius, 1.0, size) : 1.0;
    // Behind the VPL's surface, or too close to place: outside the clip volume.
    gl_Position = m.z > 0.0 && l > 0.0 ? vec4(texel / atlas * 2.0 - 1.0, v_point.x * 2.0 - 1.0, 1.0)
                                       : vec4(2.0, 2.0, 2.0, 1.0);
}
