/* lpv_simd: the 8-lane float vector layer the CPU propagation kernels are written against
 * (lpv_propagate.c, lpv_paper_step.c): AVX2+FMA intrinsics when the build targets them
 * (-march=native), otherwise plain C with fmaf. Both layers perform the same IEEE
 * operations in the same order (max/min with the x86 NaN rule), so a kernel's result never
 * depends on the thread count, and -ffp-contract=off keeps the compiler from fusing
 * operations behind the kernel's back. Internal to common/gi/ilpv; no state. */
#ifndef CAVELIGHT_LPV_SIMD_H
#define CAVELIGHT_LPV_SIMD_H

#include <math.h>
#include <string.h>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>

typedef __m256 vf;
typedef __m256i vi;
static inline vf vf_load(const float *p) { return _mm256_loadu_ps(p); }
static inline vf vf_set1(float x) { return _mm256_set1_ps(x); }
static inline vf vf_zero(void) { return _mm256_setzero_ps(); }
static inline vf vf_add(vf a, vf b) { return _mm256_add_ps(a, b); }
static inline vf vf_sub(vf a, vf b) { return _mm256_sub_ps(a, b); }
static inline vf vf_mul(vf a, vf b) { return _mm256_mul_ps(a, b); }
static inline vf vf_div(vf a, vf b) { return _mm256_div_ps(a, b); }
static inline vf vf_fma(vf a, vf b, vf c) { return _mm256_fmadd_ps(a, b, c); } /* a*b+c */
static inline vf vf_sqrt(vf a) { return _mm256_sqrt_ps(a); }
static inline vf vf_max(vf a, vf b) { return _mm256_max_ps(a, b); }
static inline vf vf_min(vf a, vf b) { return _mm256_min_ps(a, b); }
/* all-ones lanes where the comparison holds (false for NaN) */
static inline vf vf_gt(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
static inline vf vf_ge(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
static inline vf vf_and(vf a, vf m) { return _mm256_and_ps(a, m); }
static inline vf vf_sel(vf m, vf a, vf b) { return _mm256_blendv_ps(b, a, m); } /* m ? a : b */
static inline vi vi_load(const unsigned *p) { return _mm256_loadu_si256((const __m256i *)p); }
static inline vi vi_zero(void) { return _mm256_setzero_si256(); }
/* all-ones lanes whose word has bit k clear */
static inline vf vi_bit_clear(vi m, int k)
{
    __m256i b = _mm256_and_si256(m, _mm256_set1_epi32((int)(1u << k)));
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(b, _mm256_setzero_si256()));
}
static inline int vi_any(vi m) { return !_mm256_testz_si256(m, m); } /* any bit set */
static inline vi vi_or(vi a, vi b) { return _mm256_or_si256(a, b); }
static inline vf vf_lanes(int lo, int hi) /* all-ones lanes l with lo <= l < hi */
{
    __m256i l = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i in = _mm256_and_si256(_mm256_cmpgt_epi32(l, _mm256_set1_epi32(lo - 1)),
                                  _mm256_cmpgt_epi32(_mm256_set1_epi32(hi), l));
    return _mm256_castsi256_ps(in);
}
static inline void vf_store_mask(float *p, vf a, vf m)
{
    _mm256_maskstore_ps(p, _mm256_castps_si256(m), a);
}
static inline void vf_store(float *p, vf a) { _mm256_storeu_ps(p, a); }
#else
typedef struct { float v[8]; } vf;
typedef struct { unsigned v[8]; } vi;
#define VF_MAP(expr) { vf r; for (int l = 0; l < 8; l++) r.v[l] = (expr); return r; }
static inline vf vf_load(const float *p) { vf r; memcpy(r.v, p, sizeof r.v); return r; }
static inline vf vf_set1(float x) VF_MAP(x)
static inline vf vf_zero(void) VF_MAP(0.0f)
static inline vf vf_add(vf a, vf b) VF_MAP(a.v[l] + b.v[l])
static inline vf vf_sub(vf a, vf b) VF_MAP(a.v[l] - b.v[l])
static inline vf vf_mul(vf a, vf b) VF_MAP(a.v[l] * b.v[l])
static inline vf vf_div(vf a, vf b) VF_MAP(a.v[l] / b.v[l])
static inline vf vf_fma(vf a, vf b, vf c) VF_MAP(fmaf(a.v[l], b.v[l], c.v[l]))
static inline vf vf_sqrt(vf a) VF_MAP(sqrtf(a.v[l]))
/* x86 rule: the second operand when either is NaN */
static inline vf vf_max(vf a, vf b) VF_MAP(a.v[l] > b.v[l] ? a.v[l] : b.v[l])
static inline vf vf_min(vf a, vf b) VF_MAP(a.v[l] < b.v[l] ? a.v[l] : b.v[l])
static inline float lane_mask(int on) { unsigned u = on ? ~0u : 0u; float f; memcpy(&f, &u, 4); return f; }
static inline int lane_on(float m) { unsigned u; memcpy(&u, &m, 4); return u >> 31; }
static inline vf vf_gt(vf a, vf b) VF_MAP(lane_mask(a.v[l] > b.v[l]))
static inline vf vf_ge(vf a, vf b) VF_MAP(lane_mask(a.v[l] >= b.v[l]))
static inline vf vf_and(vf a, vf m) VF_MAP(lane_on(m.v[l]) ? a.v[l] : 0.0f)
static inline vf vf_sel(vf m, vf a, vf b) VF_MAP(lane_on(m.v[l]) ? a.v[l] : b.v[l])
static inline vi vi_load(const unsigned *p) { vi r; memcpy(r.v, p, sizeof r.v); return r; }
static inline vi vi_zero(void) { vi r; memset(&r, 0, sizeof r); return r; }
static inline vf vi_bit_clear(vi m, int k) VF_MAP(lane_mask(!((m.v[l] >> k) & 1u)))
static inline vi vi_or(vi a, vi b) { for (int l = 0; l < 8; l++) a.v[l] |= b.v[l]; return a; }
static inline int vi_any(vi m)
{
    unsigned any = 0;
    for (int l = 0; l < 8; l++)
        any |= m.v[l];
    return any != 0;
}
static inline vf vf_lanes(int lo, int hi) VF_MAP(lane_mask(l >= lo && l < hi))
static inline void vf_store_mask(float *p, vf a, vf m)
{
    for (int l = 0; l < 8; l++)
        if (lane_on(m.v[l]))
            p[l] = a.v[l];
}
static inline void vf_store(float *p, vf a) { memcpy(p, a.v, sizeof a.v); }
#endif

#define ALWAYS_INLINE inline __attribute__((always_inline))

#endif
