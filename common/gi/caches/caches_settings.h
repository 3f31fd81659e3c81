/* caches_settings: the caches method's settings (gi_settings.h), without GL: what every
 * program needs to name, check and send them. The RSM size is the frame's own "rsm"
 * transport setting, shared with every method. */
#ifndef CAVELIGHT_CACHES_SETTINGS_H
#define CAVELIGHT_CACHES_SETTINGS_H

#include "gi/gi_settings.h"

/* Which VALs light the caches. */
typedef enum caches_selection {
    CACHES_SELECT_IMPORTANCE = 0, /* caches-vals of them by importance (val_select.h) */
    CACHES_SELECT_ALL,            /* every RSM texel: plain LightSkin, the comparison */
} caches_selection;

/* How the proxy lights are occluded (cache_light.h). */
typedef enum caches_occlusion {
    CACHES_OCCLUSION_APPROX = 0,  /* the caches' disks, projected (the paper's) */
    CACHES_OCCLUSION_EXACT,       /* a ray from every cache to every VAL (the ceiling) */
    CACHES_OCCLUSION_OFF,         /* none: to measure what occlusion does */
} caches_occlusion;

/* Whether each cache also makes a glossy proxy light (cache_light.h). */
typedef enum caches_glossy {
    CACHES_GLOSSY_OFF = 0,        /* diffuse indirect light only */
    CACHES_GLOSSY_ON,             /* and a view-dependent specular indirect term */
} caches_glossy;

/* caches-vals: the paper selects 2048 to 8192 VALs; 16384 is the upper end. */
enum { CACHES_VALS_MIN = 256, CACHES_VALS_MAX = 16384, CACHES_VALS_DEFAULT = 2048 };
/* caches-view-samples: the paper uses 512 and found 256 enough. */
enum { CACHES_VIEW_SAMPLES_MIN = 16, CACHES_VIEW_SAMPLES_MAX = 1024,
       CACHES_VIEW_SAMPLES_DEFAULT = 256 };

typedef struct caches_settings {
    int vals;                     /* VALs selected per frame */
    caches_selection selection;
    int view_samples;             /* rays from the head for the importance */
    float density;                /* caches per m^2; 0: auto (cache_place.h) */
    float angle;                  /* the angle tolerance, degrees */
    caches_occlusion occlusion;
    int seed;                     /* the selection's fixed jitter */
    caches_glossy glossy;
} caches_settings;

extern const gi_method_settings caches_settings_table;

/* The frame's caches settings. */
void caches_settings_get(const frame_params *p, caches_settings *out);

#endif
