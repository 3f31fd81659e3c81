// The presentation pass (node/present/present_warp.c): one triangle over the projector image, or
// a warp mesh's cells (u_mesh), whose vertices carry the point they show and their weight.
layout(location = 0) in vec4 a_vertex; // mesh: x y (projector image, 0..1) u v (rendered image)
layout(location = 1) in float a_weight;

uniform int u_mesh;

out vec2 v_uv;
out float v_weight;

void main()
{
    if (u_mesh != 0) {
        v_uv = a_vertex.zw;
        v_weight = a_weight;
        gl_Position = vec4(a_vertex.xy * 2.0 - 1.0, 0.0, 1.0);
    } else {
        vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
        v_uv = p;
        v_weight = 1.0;
        gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    }
}
