// One cube face of a VPL's shadow map (node/gi_vpl.c): the distance from the VPL to the
// nearest surface, over u_far, so shade.frag compares distances whatever the face.
in vec3 v_position;

uniform vec3 u_vpl_position;
uniform float u_far;

void main()
{
    gl_FragDepth = length(v_position - u_vpl_position) / u_far;
}
