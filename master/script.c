/* script: the scripted head and lamp path (script.h). */
#include "script.h"

#include <math.h>
#include <string.h>

void script_init(script *s, const cluster_config *cfg)
{
    memset(s, 0, sizeof *s);
    memcpy(s->home, cfg->observer.home, sizeof s->home);
}

/* The head pose at time t in CAVE space (column-major). */
static void script_head(const script *s, double t, float m[16])
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

/* The lamp's angle on its circle: whole glides so far, then an eased glide (smoothstep:
 * it starts and stops without a jump) in the first half of the period, then a rest. */
static double lamp_angle(double t)
{
    double cycles = floor(t / SCRIPT_LAMP_PERIOD_S);
    double x = (t - cycles * SCRIPT_LAMP_PERIOD_S) / (0.5 * SCRIPT_LAMP_PERIOD_S);
    x = x < 1.0 ? x : 1.0;
    return SCRIPT_LAMP_ARC * (cycles + x * x * (3.0 - 2.0 * x));
}

void script_frame(const script *s, double t, frame_params *f)
{
    f->time = t;
    script_head(s, t, f->head);
    if (f->light_count < 1)
        return;
    frame_light *l = &f->lights[0];
    double a = lamp_angle(t);
    l->type = SCENE_LIGHT_POINT;
    l->position[0] = s->home[0] + SCRIPT_LAMP_RADIUS_M * (float)cos(a);
    l->position[1] = s->home[1] + SCRIPT_LAMP_RISE_M;
    l->position[2] = s->home[2] + SCRIPT_LAMP_RADIUS_M * (float)sin(a);
}
