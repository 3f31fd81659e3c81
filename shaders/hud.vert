// HUD meshes (node/renderer_hud.c): model space -> world (u_model) -> the eye's clip space.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;

void main()
{
    vec4 world = u_model * vec4(in_position, 1.0);
    v_position = world.xyz;
    // Models are scaled per axis (bars, cones): normals need the inverse transpose.
    v_normal = transpose(inverse(mat3(u_model))) * in_normal;
    gl_Position = u_view_projection * world;
}
