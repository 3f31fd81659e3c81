// Scene geometry for the G-buffer and the RSM: the triangles as loaded, placed by their
// object's model (identity for static triangles; scene_gl.c sets both per draw), one
// view-projection.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_view_projection;
uniform mat4 u_model;          // the object's model matrix (scene_pose.h)
uniform mat3 u_normal_model;   // its normals': the cofactors of its 3x3 (normalized later)

out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;

void main()
{
    vec4 p = u_model * vec4(in_position, 1.0);
    v_position = p.xyz;
    v_normal = u_normal_model * in_normal;
    v_uv = in_uv;
    gl_Position = u_view_projection * p;
}
