/* frame_view: the view of one eye, built the same way wherever the node renders one.
 *
 * One rule for every view (standalone cameras and screens, cluster screens, benchmarks):
 * the eyes of a head sit offaxis_stereo_eyes() apart along the head's right axis; the
 * near plane is FRAME_VIEW_NEAR_PLANE; the far plane is the caller's (scene_far_plane()).
 * Screens get Kooima's off-axis frustum (offaxis_screen()), cameras a symmetric perspective
 * or an orthographic one. A scene file's camera keeps its own clip planes where the file
 * gives them. Pure maths, no GL. */
#ifndef CAVELIGHT_FRAME_VIEW_H
#define CAVELIGHT_FRAME_VIEW_H

#include "scene/scene.h"

/* 2 cm: closer than the eye can focus (its near point is about 7 cm even in children), so
 * nothing a user can look at is clipped; the depth buffer is 32-bit float. */
#define FRAME_VIEW_NEAR_PLANE 0.02f
/* The default distance between the eyes: a typical adult interpupillary distance (64 mm;
 * the observer's eye_separation in a cluster config overrides it). */
#define FRAME_VIEW_EYE_SEPARATION 0.064f

typedef struct frame_view {
    float view[16];        /* world-to-eye, column-major */
    float projection[16];  /* eye-to-clip (off-axis or symmetric) */
    float eye_position[3]; /* world space */
    int width, height;
} frame_view;

/* The point between the eyes in CAVE space: the tracked head pose (column-major) times
 * head_to_eye, the tracker sensor's offset from that point in head space (zeros: the
 * sensor itself). The one rule for where the viewer is (the eyes, the GI's view samples). */
void frame_view_head_centre(const float head[16], const float head_to_eye[3], float out[3]);
/* The eye of a head at `head` with unit right axis `right`: side -1 left, +1 right,
 * 0 the head itself (mono). */
void frame_view_eye(const float head[3], const float right[3], float separation, int side,
                    float eye[3]);
/* Through a screen given by three corners, all in world space. An eye nearer the screen's
 * plane than FRAME_VIEW_NEAR_PLANE, or behind it, is moved along the screen's normal to
 * FRAME_VIEW_NEAR_PLANE in front (nearer, the screen itself would lie before the near
 * plane and be clipped away): a tracked head walking into a wall never ends a session.
 * Returns 0, 1 when the eye was moved (*distance, if not NULL: how far in front it was,
 * negative behind), or -1 when the corners are degenerate or the eye is not finite. */
int frame_view_screen(const float bottom_left[3], const float bottom_right[3],
                      const float top_left[3], const float eye[3], float far_plane, int width,
                      int height, frame_view *out, float *distance);
/* A symmetric camera at eye looking at target, yfov in radians. Returns 0, or -1 when eye
 * equals target. */
int frame_view_camera(const float eye[3], const float target[3], float yfov, float far_plane,
                      int width, int height, frame_view *out);
/* Through a scene camera (scene_default_camera()) from eye (its position, or a stereo eye
 * beside it), looking its way with its up: perspective, or orthographic (shaded as seen
 * from far along its axis: the renderer takes the view's direction), with the image's
 * aspect; its znear and zfar where the file gives them. Returns 0, or -1 for a degenerate
 * camera. */
int frame_view_scene_camera(const scene_camera *c, const float eye[3], float far_plane,
                            int width, int height, frame_view *out);

#endif
