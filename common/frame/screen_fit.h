/* screen_fit: the rectangle nearest to measured screen corners (least squares).
 *
 * Measured corners are never exactly a rectangle (a tape, a tracker, a projector's keystone
 * correction all add millimetres), but the off-axis projection needs one. Given the
 * bottom-left, bottom-right and top-left corners (and the top-right one when measured),
 * screen_fit_rectangle() finds the rectangle whose corners lie nearest to them: least
 * squared distance summed over the given corners, over every position, orientation, width
 * and height. With four corners that is closed form: the centre is the corners' mean, and
 * the axes are the in-plane angle that maximises the explained spread (atan2 of two
 * sums). With three, the missing corner is filled in from the current fit and the fit
 * repeated (an EM step: the three corners' squared error never grows) until it no longer
 * moves. The deviation is the largest distance a given corner moved. Pure maths, doubles. */
#ifndef CAVELIGHT_SCREEN_FIT_H
#define CAVELIGHT_SCREEN_FIT_H

typedef struct screen_fit {
    float bottom_left[3], bottom_right[3], top_left[3]; /* the rectangle */
    double deviation;   /* metres: the largest distance between a given corner and the fit */
    int iterations;     /* fits done (1 with four corners) */
} screen_fit;

/* top_right may be NULL. Returns 0, or -1 when the corners span no rectangle (an edge of
 * zero length, or the corners on one line). */
int screen_fit_rectangle(const float bottom_left[3], const float bottom_right[3],
                         const float top_left[3], const float *top_right, screen_fit *out);

#endif
