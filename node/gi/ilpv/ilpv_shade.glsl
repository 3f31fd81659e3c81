// The ILPV method's shading snippet (gi_method.h): irradiance from the LPV's three SH
// textures (node/gi/ilpv/gi_ilpv.h), compiled after shaders/shade.frag.
uniform int u_lpv_enabled;
uniform sampler3D u_lpv_r;           // texelFetch only
uniform sampler3D u_lpv_g;
uniform sampler3D u_lpv_b;
uniform vec3 u_lpv_origin;
uniform float u_lpv_cell;
uniform ivec3 u_lpv_size;            // cells per axis
uniform float u_lpv_behind;          // LPV_RECEIVE_BEHIND (lpv_receive.h): cells behind
                                     // the surface that still count
uniform int u_lpv_paper;             // 1: the `paper` transport's receiver

// What one colour's SH coefficients L of a cell give a surface with normal n, per unit
// area (lpv_receive.h, the same rule): energy E and mean direction d with mean cosine q,
// read as the closest of beam (q = 1), clamped cosine (2/3), hemisphere (1/2) and isotropic
// light (0), whose irradiance on the surface is known in closed form, mixed linearly in q.
float lpv_closure(vec4 L, vec3 n)
{
    float e = SH_ENERGY * L.x;
    if (!(e > 0.0))
        return 0.0;
    vec3 f = vec3(-L.w, -L.y, L.z) * (1.0 / SH_Y1);
    float len = sqrt(dot(f, f));
    float q = min(len / e, 1.0);
    float t = len > 0.0 ? clamp(-dot(f, n) / len, -1.0, 1.0) : 0.0;
    float theta = acos(t);
    float beam = max(t, 0.0);
    float lobe = ((PI - theta) * t + sin(theta)) * (2.0 / (3.0 * PI));
    float hemi = 0.25 * (1.0 + t), iso = 0.25;
    float g;
    if (q >= 2.0 / 3.0)
        g = mix(lobe, beam, 3.0 * q - 2.0);
    else if (q >= 0.5)
        g = mix(hemi, lobe, 6.0 * q - 3.0);
    else
        g = mix(iso, hemi, 2.0 * q);
    return e * g;
}

// Irradiance from the LPV at surface point p with normal n (lpv_receive.h): the eight
// cells around p, trilinear weights, keeping only the cells whose centre lies in front of
// the surface's plane (light behind a wall must not reach its front) by less than the own
// layer (lpv_own_layer(): the surface's own light is kept out of it), then the closure.
vec3 lpv_irradiance(vec3 p, vec3 n)
{
    vec3 q = (p - u_lpv_origin) / u_lpv_cell - 0.5;
    vec3 i0 = floor(q), f = q - i0;
    vec4 lr = vec4(0.0), lg = vec4(0.0), lb = vec4(0.0);
    float wsum = 0.0;
    vec3 an = abs(n);
    float layer = (0.5 * (an.x + an.y + an.z) + 0.5 - u_lpv_behind) * u_lpv_cell;
    for (int k = 0; k < 8; k++) {
        ivec3 o = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        vec3 w3 = mix(1.0 - f, f, vec3(o));
        float w = w3.x * w3.y * w3.z;
        vec3 centre = u_lpv_origin + (i0 + vec3(o) + 0.5) * u_lpv_cell;
        float ahead = dot(centre - p, n);
        if (ahead < -u_lpv_behind * u_lpv_cell || ahead >= layer || !(w > 0.0))
            continue;
        ivec3 c = clamp(ivec3(i0) + o, ivec3(0), u_lpv_size - 1);
        lr += w * texelFetch(u_lpv_r, c, 0);
        lg += w * texelFetch(u_lpv_g, c, 0);
        lb += w * texelFetch(u_lpv_b, c, 0);
        wsum += w;
    }
    if (!(wsum > 0.0))
        return vec3(0.0);
    return vec3(lpv_closure(lr / wsum, n), lpv_closure(lg / wsum, n), lpv_closure(lb / wsum, n)) /
           (u_lpv_cell * u_lpv_cell);
}

// The thesis's receiver (its algorithm 3, `paper`): the lattice sampled trilinearly half a
// cell out along the normal, each colour projected on SH_cos(-n), per cell area.
vec3 lpv_irradiance_paper(vec3 p, vec3 n)
{
    vec3 q = (p + 0.5 * u_lpv_cell * n - u_lpv_origin) / u_lpv_cell - 0.5;
    vec3 i0 = floor(q), f = q - i0;
    vec4 c = sh_cosine_lobe(-n);
    vec3 e = vec3(0.0);
    for (int k = 0; k < 8; k++) {
        ivec3 o = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        vec3 w3 = mix(1.0 - f, f, vec3(o));
        ivec3 t = clamp(ivec3(i0) + o, ivec3(0), u_lpv_size - 1);
        e += (w3.x * w3.y * w3.z) * vec3(dot(c, texelFetch(u_lpv_r, t, 0)),
                                         dot(c, texelFetch(u_lpv_g, t, 0)),
                                         dot(c, texelFetch(u_lpv_b, t, 0)));
    }
    return max(e, vec3(0.0)) / (u_lpv_cell * u_lpv_cell);
}

vec3 gi_irradiance(vec3 p, vec3 n)
{
    if (u_lpv_enabled == 0)
        return vec3(0.0);
    return u_lpv_paper != 0 ? lpv_irradiance_paper(p, n) : lpv_irradiance(p, n);
}
