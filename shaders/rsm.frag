// Reflective shadow map of one light view (paper 3.3, [KD10]): position, normal and the
// flux each texel reflects. Spots and a point light's cube faces are perspective views: a
// texel subtends solid angle d_omega from the light, the flux arriving through it is
// I(omega) d_omega whatever the distance and slant. A directional light's view is
// orthographic: a texel's window area A receives E A. A Lambertian surface reflects albedo
// times that. Depth and the plane (normal, offset) are the shadow map (shade.frag).
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;

uniform vec4 u_base_color;
uniform int u_has_texture;
uniform sampler2D u_base_texture;
uniform int u_light_type;
uniform vec3 u_light_position;
uniform vec3 u_light_direction;
uniform vec3 u_light_radiance;      // colour * intensity: W/sr (spot, point), W/m^2 (directional)
uniform float u_cos_outer, u_cos_inner;
uniform float u_tan_half_fov;        // perspective views
uniform float u_vpl_tan;             // texels within +-u_vpl_tan on the image plane carry flux
uniform float u_texel_area;          // orthographic views: a texel's window, m^2
uniform float u_travel0;             // directional: distance travelled in the medium at the origin
uniform float u_size;                // RSM edge in texels
uniform float u_absorption;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_flux;

void main()
{
    vec3 n = normalize(v_normal);
    vec4 albedo = u_base_color;
    if (u_has_texture != 0)
        albedo *= texture(u_base_texture, v_uv);
    vec3 flux;
    if (u_light_type == LIGHT_DIRECTIONAL) {
        if (dot(n, u_light_direction) > 0.0)
            n = -n;
        float travel = dot(v_position, u_light_direction) + u_travel0;
        flux = albedo.rgb * u_light_radiance * u_texel_area * transmittance(u_absorption, travel);
    } else {
        vec3 to_light = u_light_position - v_position;
        float r = length(to_light);
        if (dot(n, to_light) < 0.0)
            n = -n;
        vec2 ndc = gl_FragCoord.xy / u_size * 2.0 - 1.0;
        vec2 img = ndc * u_tan_half_fov;   // on the image plane at distance 1
        float texel = 2.0 * u_tan_half_fov / u_size;
        float d_omega = texel * texel / pow(1.0 + dot(img, img), 1.5);
        float cone = u_light_type == LIGHT_SPOT
                         ? spot_factor(-to_light / r, u_light_direction, u_cos_outer, u_cos_inner)
                         : 1.0;
        // A cube face's margin belongs to the neighbouring face: no flux counted twice.
        if (any(greaterThan(abs(img), vec2(u_vpl_tan))))
            cone = 0.0;
        flux = albedo.rgb * u_light_radiance * cone * d_omega * transmittance(u_absorption, r);
    }
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, -dot(n, v_position));   // the plane, for the shadow test
    out_flux = vec4(flux, 0.0);
}
