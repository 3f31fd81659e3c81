// An application's points and lines (node/app_draw.c) into the G-buffer: world-space
// vertices with a normal (zero: facing the eye) and an albedo each.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_color;

uniform mat4 u_view_projection;
uniform vec4 u_eye;        // the eye (w 1), or the direction towards it (w 0)
uniform float u_point_size;

out vec3 v_position;
out vec3 v_normal;
out vec3 v_color;

void main()
{
    vec3 towards = u_eye.xyz - in_position * u_eye.w;
    v_position = in_position;
    v_normal = dot(in_normal, in_normal) > 0.0 ? in_normal : towards;
    v_color = in_color;
    gl_PointSize = u_point_size;
    gl_Position = u_view_projection * vec4(in_position, 1.0);
}
