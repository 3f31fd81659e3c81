#include "frame/frame_view.h"

#include <string.h>

#include "base/mat4.h"
#include "frame/offaxis.h"

void frame_view_head_centre(const float head[16], const float head_to_eye[3], float out[3])
{
    mat4_transform_point(head, head_to_eye, out);
}

void frame_view_eye(const float head[3], const float right[3], float separation, int side,
                    float eye[3])
{
    float eyes[2][3];
    offaxis_stereo_eyes(head, right, separation, eyes[0], eyes[1]);
    memcpy(eye, side < 0 ? eyes[0] : side > 0 ? eyes[1] : head, 3 * sizeof(float));
}

static void begin(const float eye[3], int width, int height, frame_view *out)
{
    memset(out, 0, sizeof *out);
    memcpy(out->eye_position, eye, sizeof out->eye_position);
    out->width = width;
    out->height = height;
}

int frame_view_screen(const float bottom_left[3], const float bottom_right[3],
                      const float top_left[3], const float eye[3], float far_plane, int width,
                      int height, frame_view *out, float *distance)
{
    offaxis_screen_desc d = {.near_plane = FRAME_VIEW_NEAR_PLANE, .far_plane = far_plane};
    int moved = offaxis_eye_in_front(bottom_left, bottom_right, top_left, eye,
                                     FRAME_VIEW_NEAR_PLANE, d.eye, distance);
    if (moved < 0)
        return -1;
    memcpy(d.bottom_left, bottom_left, sizeof d.bottom_left);
    memcpy(d.bottom_right, bottom_right, sizeof d.bottom_right);
    memcpy(d.top_left, top_left, sizeof d.top_left);
    begin(d.eye, width, height, out);
    return offaxis_screen(&d, out->view, out->projection) != 0 ? -1 : moved;
}

int frame_view_camera(const float eye[3], const float target[3], float yfov, float far_plane,
                      int width, int height, frame_view *out)
{
    scene_camera c = {.valid = 1, .yfov = yfov};
    memcpy(c.position, eye, sizeof c.position);
    memcpy(c.target, target, sizeof c.target);
    return frame_view_scene_camera(&c, eye, far_plane, width, height, out);
}

int frame_view_scene_camera(const scene_camera *c, const float eye[3], float far_plane,
                            int width, int height, frame_view *out)
{
    begin(eye, width, height, out);
    float target[3];
    for (int i = 0; i < 3; i++)
        target[i] = c->target[i] + eye[i] - c->position[i];
    if (offaxis_view(eye, target, c->up, out->view) != 0)
        return -1;
    float aspect = (float)width / (float)height;
    float near_plane = c->znear > 0 ? c->znear : FRAME_VIEW_NEAR_PLANE;
    float far_clip = c->zfar > near_plane ? c->zfar : far_plane;
    if (c->orthographic)
        offaxis_orthographic(-c->ymag * aspect, c->ymag * aspect, -c->ymag, c->ymag, near_plane,
                             far_clip, out->projection);
    else
        offaxis_perspective(c->yfov, aspect, near_plane, far_clip, out->projection);
    return 0;
}
