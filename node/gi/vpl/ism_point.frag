// A point's texels (shaders/ism_point.vert): its record, nearest wins (depth test). A splat
// covers its disk within its own tile only.
flat in vec4 v_point;
flat in vec4 v_tile;

uniform int u_splat;

layout(location = 0) out vec4 out_point;

void main()
{
    vec2 c = gl_FragCoord.xy;
    if (u_splat != 0 && (any(lessThan(c, v_tile.xy)) || any(greaterThanEqual(c, v_tile.zw)) ||
                         distance(c, v_point.yz) > max(v_point.w, 0.5)))
        discard;
    out_point = v_point;
}
