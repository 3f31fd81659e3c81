#include "script.h"

#include <math.h>
#include <string.h>

void script_init(script *s, const cluster_config *cfg, const params_store *start)
{
    memset(s, 0, sizeof *s);
    memcpy(s->home, cfg->observer.home, sizeof s->home);
    frame_params f;
    params_to_frame(start, &f);
    s->have_light = f.light_count > 0;
    if (s->have_light)
        s->light0 = f.lights[0];
}

void script_head(const script *s, double t, float m[16])
{
    float yaw = (float)(0.3 * sin(0.6 * t));
    float c = cosf(yaw), sn = sinf(yaw);
    memset(m, 0, 16 * sizeof *m);
    /* Rotation about y, then translation: column-major. */
    m[0] = c;
    m[2] = -sn;
    m[5] = 1;
    m[8] = sn;
    m[10] = c;
    m[12] = s->home[0] + (float)(0.25 * sin(0.8 * t));
    m[13] = s->home[1] + (float)(0.05 * sin(1.3 * t));
    m[14] = s->home[2] + (float)(0.15 * sin(0.5 * t));
    m[15] = 1;
}

void script_apply(const script *s, double t, params_store *p)
{
    float head[16];
    script_head(s, t, head);
    params_set_f64(p, PARAMS_TIME, t);
    params_set_mat4(p, PARAMS_HEAD, head);
    if (!s->have_light)
        return;
    const frame_light *l = &s->light0;
    float a = (float)(0.7 * t), swing = (float)(0.25 * sin(0.9 * t));
    float pose[6] = {
        l->position[0] + 0.3f * cosf(a), l->position[1], l->position[2] + 0.3f * sinf(a),
        l->direction[0], l->direction[1], l->direction[2],
    };
    /* Swing the axis about z, keep it unit length. */
    float dx = pose[3] * cosf(swing) - pose[4] * sinf(swing);
    float dy = pose[3] * sinf(swing) + pose[4] * cosf(swing);
    float len = sqrtf(dx * dx + dy * dy + pose[5] * pose[5]);
    pose[3] = dx / len;
    pose[4] = dy / len;
    pose[5] /= len;
    params_set(p, params_light_key(0, PARAMS_LIGHT_POSE), pose, sizeof pose);
}
