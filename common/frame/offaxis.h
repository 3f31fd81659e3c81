/* offaxis: view and projection matrices for screens, cameras and light views.
 *
 * offaxis_screen(): Kooima's generalized perspective projection. A screen is given by its
 * bottom-left, bottom-right and top-left corners in world space, the eye by its position;
 * the result is a view matrix (world to eye, looking along the screen's -normal, axes
 * aligned with the screen) and an asymmetric frustum whose near plane is the screen
 * scaled to the near distance. Matrices are column-major, OpenGL clip conventions. */
#ifndef CAVELIGHT_OFFAXIS_H
#define CAVELIGHT_OFFAXIS_H


typedef struct offaxis_screen_desc {
    float bottom_left[3], bottom_right[3], top_left[3];
    float eye[3];
    float near_plane, far_plane; /* 0 = 0.05, 100 */
} offaxis_screen_desc;

/* Returns 0, or -1 when the corners are degenerate or the eye lies in the screen plane. */
int offaxis_screen(const offaxis_screen_desc *desc, float view[16], float projection[16]);

/* The eye offaxis_screen() can use: eye itself when it lies at least min_distance in front
 * of the screen's plane (on the side its normal, right x up, points to), else eye moved
 * along the normal to min_distance in front. Returns 0 (unchanged), 1 (moved; *distance
 * is how far in front it was, negative behind), or -1 when the corners are degenerate or
 * the eye is not finite. */
int offaxis_eye_in_front(const float bottom_left[3], const float bottom_right[3],
                         const float top_left[3], const float eye[3], float min_distance,
                         float out[3], float *distance);

/* Symmetric perspective camera at position looking at target, up = +y (or +z when the
 * view is vertical). yfov in radians. Returns -1 if position == target. */
int offaxis_look_at(const float position[3], const float target[3], float yfov, float aspect,
                    float near_plane, float far_plane, float view[16], float projection[16]);
/* The parts of a camera: the view matrix of an eye at position looking at target with the
 * given up (NULL or zero: +y, or +z when the view is vertical; -1 if position == target or
 * up lies along the view), a symmetric perspective projection, and an orthographic one
 * over the window [left, right] x [bottom, top] in eye space. */
int offaxis_view(const float position[3], const float target[3], const float *up,
                 float view[16]);
void offaxis_perspective(float yfov, float aspect, float near_plane, float far_plane,
                         float projection[16]);
void offaxis_orthographic(float left, float right, float bottom, float top, float near_plane,
                          float far_plane, float projection[16]);

/* Eye positions for stereo: the head position offset by +-separation/2 along `right`. */
void offaxis_stereo_eyes(const float head[3], const float right[3], float separation,
                         float left_eye[3], float right_eye[3]);

#endif
