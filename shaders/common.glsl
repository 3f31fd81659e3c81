// Shared by every cavelight shader (prepended after the #version line by the renderer).
const float PI = 3.14159265358979;
const float SH_C0 = 0.886226925452758;  // sqrt(pi) / 2
const float SH_C1 = 1.023326707946488;  // sqrt(pi / 3)
const int MAX_LIGHTS = 8;
const int MAX_LIGHT_VIEWS = 48;           // light_view.h: six cube faces per light
const int LIGHT_SPOT = 0;                 // scene_light_type
const int LIGHT_POINT = 1;
const int LIGHT_DIRECTIONAL = 2;

// Clamped-cosine lobe around unit n in 2-band SH (paper 3.3.1, same signs as the CPU core).
vec4 sh_cosine_lobe(vec3 n)
{
    return vec4(SH_C0, -SH_C1 * n.y, SH_C1 * n.z, -SH_C1 * n.x);
}

// The specular lobe every pass shades with (normalized Blinn-Phong, a dielectric's
// reflectance SPECULAR_F0): exponent m = 2 / alpha^2 - 2 from roughness (alpha = roughness^2,
// bounded so that a mirror stays finite), f_s = (m + 8) / (8 pi) F0 (n . h)^m for half
// vector h. common/gi/caches/cache_light.c has the host's copy.
const float SPECULAR_F0 = 0.04;

float specular_exponent(float roughness)
{
    float alpha = roughness * roughness;
    return 2.0 / max(alpha * alpha, 1e-3) - 2.0;
}

float specular_brdf(float m, vec3 n, vec3 h)
{
    return (m + 8.0) / (8.0 * PI) * SPECULAR_F0 * pow(max(dot(n, h), 0.0), m);
}

// f_s between unit directions wo and wi (0 when they are opposite).
float specular_between(float m, vec3 n, vec3 wo, vec3 wi)
{
    vec3 h = wo + wi;
    return dot(h, h) > 0.0 ? specular_brdf(m, n, normalize(h)) : 0.0;
}

// Direct3D-style spot cone: 1 inside the inner angle, 0 outside the outer, linear between.
float spot_factor(vec3 to_surface, vec3 axis, float cos_outer, float cos_inner)
{
    float c = dot(to_surface, axis);
    return clamp((c - cos_outer) / max(cos_inner - cos_outer, 1e-4), 0.0, 1.0);
}

// Share of light surviving distance r through a medium with per-metre absorption
// probability sigma (same law as the LPV's absorption).
float transmittance(float sigma, float r)
{
    return sigma > 0.0 ? pow(1.0 - min(sigma, 0.999999), r) : 1.0;
}

// SH basis constants (lpv/sh.h): Y0 = 1 / (2 sqrt pi), Y1 = sqrt(3 / (4 pi)); <L|1> = SH_ENERGY L0.
const float SH_Y0 = 0.282094791773878;
const float SH_Y1 = 0.488602511902920;
const float SH_ENERGY = 3.544907701811032;

// Paraboloid projection of the hemisphere around unit n (a VPL's imperfect shadow map,
// node/vpl_ism.h) of direction d: xy in the unit disk, z the cosine to n (<= 0: behind).
// The frame around n is Duff et al.'s branchless orthonormal basis. The map is conformal:
// a small disk of radius r at distance l covers r / (l (1 + z)) of the unit disk's radius.
vec3 ism_project(vec3 n, vec3 d)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z), b = n.x * n.y * a;
    vec3 t1 = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 t2 = vec3(b, s + n.y * n.y * a, -n.y);
    vec3 w = normalize(d);
    float z = dot(w, n);
    return vec3(vec2(dot(w, t1), dot(w, t2)) / (1.0 + z), z);
}
