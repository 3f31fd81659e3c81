/* lpv_objects: the blockers (lpv_geometry.h) of a scene whose objects move
 * (scene_pose.h), kept bit for bit equal to a fresh build from the frame's pose: the static
 * triangles' bits, ORed with every shown object's triangles where its model puts them.
 *
 * A triangle sets bits only in the cells of its box grown by two (its segments' both
 * ends), so when objects move only those cells change: lpv_objects_update() marks the
 * cells around each moved object's old and new place, puts the static bits back there and
 * adds again the triangles of every shown object near them. Triangles in any order give
 * the same bits, so a node that builds the blockers fresh for the current pose (a late
 * joiner, a rebuilt method) agrees with one that followed every move. Not the light, not
 * GL: the caller uploads the blockers where its backend needs them. */
#ifndef CAVELIGHT_LPV_OBJECTS_H
#define CAVELIGHT_LPV_OBJECTS_H

#include <stddef.h>
#include <stdint.h>

#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_geometry.h"
#include "scene/scene.h"

typedef struct lpv_objects {
    lpv_blockers fixed;           /* the static triangles' bits */
    int count;                    /* the scene's objects */
    int box[SCENE_MAX_OBJECTS][6];/* cells each object's bits may touch (lo, hi), lo > hi:
                                     none (hidden) */
    size_t *first;                /* per object (and one more): its triangles in `tri` */
    size_t *tri;                  /* triangle indices grouped by object */
    float *moved_positions;       /* scratch: one object's triangles through its model */
    uint8_t *dirty;               /* scratch: one flag per cell */
} lpv_objects;

typedef struct lpv_objects_stats {
    int objects_moved;
    size_t cells_redone;          /* cells put back to the static bits and redone */
    size_t triangles_added;       /* object triangles added again */
} lpv_objects_stats;

/* The static bits, and b (of lat's size, all clear) set for the scene as loaded (every
 * object at rest and shown). Returns 0, or -1 when out of memory. */
int lpv_objects_init(lpv_objects *o, lpv_blockers *b, const lattice_desc *lat, const scene *s);
void lpv_objects_free(lpv_objects *o);
/* Objects flagged in moved (model or visibility changed) go to model[k] (shown[k] 0:
 * hidden). stats may be NULL. */
void lpv_objects_update(lpv_objects *o, lpv_blockers *b, const lattice_desc *lat, const scene *s,
                        const float (*model)[16], const uint8_t *shown, const uint8_t *moved,
                        lpv_objects_stats *stats);

#endif
