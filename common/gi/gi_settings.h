/* gi_settings: the GI methods as every program knows them, without GL.
 *
 * The registry (gi_methods.def) names the methods; each brings a table of its settings
 * (gi_method_settings, in node/gi/NAME/NAME_settings.c). From them this module makes
 * the one list of GI options every program shares: the frame's own transport settings
 * (frame_transport_settings[]: steps, lambda, medium, RSM size), the method choice "gi",
 * every method's settings, each in a slot of frame_params.gi_settings, and last the
 * frame's display settings (frame_display_settings[]: env, display gamma, exposure), which
 * travel the same way. With it:
 *   - the node's and the master's command lines and the cluster config's "settings" take
 *     the same names, ranges and defaults, parsed by one function (gi_set());
 *   - the parameter store has a key for each (gi_params_schema()), so the master sets
 *     every setting for every node and a late joiner gets them in its snapshot;
 *   - a node clamps what it received once per frame (gi_frame_sanitize());
 *   - a method reads its settings as its own struct (gi_settings_read()).
 * Not here: what a method does (gi_method.h). */
#ifndef CAVELIGHT_GI_SETTINGS_H
#define CAVELIGHT_GI_SETTINGS_H

#include "base/cli.h"
#include "base/setting.h"
#include "cluster/cluster_config.h"
#include "cluster/params.h"
#include "frame/frame_params.h"

struct gi_cost;

/* What a method's settings file defines. */
typedef struct gi_method_settings {
    const char *name;      /* "vpl": the value of --gi */
    const char *summary;   /* a few words for --gi's help */
    const setting *rows;   /* offsets into the method's settings struct */
    int count;
    size_t struct_size;    /* that struct's size */
    /* Optional: what no single row can say (two settings that exclude each other), from
     * the slots a command line or config set; NULL or one line. */
    const char *(*check)(const frame_params *p);
    /* Optional: the frame's work and memory for this method (gi_cost.h); NULL: nothing
     * worth bounding. */
    void (*cost)(const frame_params *p, const float bounds_min[3], const float bounds_max[3],
                 struct gi_cost *out);
    /* Optional: --budget-ms's rule for this method (gi_budget.h); NULL: none. */
    const struct gi_budget_rule *budget;
} gi_method_settings;

/* Each method's index in the registry, known when it is compiled: GI_METHOD_ID(vpl). */
enum gi_method_id {
#define GI_METHOD(name) GI_METHOD_ID_##name,
#include "gi/gi_methods.def"
#undef GI_METHOD
    GI_METHOD_ID_COUNT
};
#define GI_METHOD_ID(name) GI_METHOD_ID_##name

int gi_method_count(void);
const gi_method_settings *gi_method_at(int method);
/* The method named name, or -1. */
int gi_method_find(const char *name);
/* "ilpv", "none", "vpl", ..., in registry order (gi_method_count() names). */
const char *const *gi_method_names(void);

/* One option: a transport setting of the frame, the method choice, a method's setting, or
 * a display setting of the frame. */
typedef struct gi_option {
    const setting *row;
    int method;            /* its method, or -1 (the frame's and "gi") */
    int slot;              /* >= 0: frame_params.gi_settings[slot]; else a frame field */
    int display;           /* 1: a display setting (--help lists it apart) */
} gi_option;

int gi_option_count(void);
const gi_option *gi_option_at(int i);
/* The option named name, or NULL. */
const gi_option *gi_option_find(const char *name);
/* Its value in p (an unset slot: the default). */
setting_value gi_option_get(const gi_option *o, const frame_params *p);
/* Sets it in p (a slot becomes set). */
void gi_option_put(const gi_option *o, setting_value v, frame_params *p);
/* 1 when p's slot of o is set (always 1 for a frame field). */
int gi_option_is_set(const gi_option *o, const frame_params *p);

/* Parses text as the option named name and sets it in p: NULL, or the reason it is
 * refused ("a whole number in 64..4096"; an unknown name: "not a GI setting (did you mean
 * vpl-count?)"). The one validation of every program. */
const char *gi_set(frame_params *p, const char *name, const char *text);
/* The same for a number, formatted first ("%d" or "%g"). */
const char *gi_set_number(frame_params *p, const char *name, double value);
/* The option's value in p as text ("256", "ism"); "" for an unknown name. */
const char *gi_get_text(const frame_params *p, const char *name, char *buf, size_t cap);
/* The cluster config's "settings" into p (gi_set() each, then gi_check()): 0, or -1 with
 * "cluster config FILE: settings.NAME: reason" in err. */
int gi_set_config(const cluster_config *cfg, frame_params *p, char *err, size_t errlen);
/* Every method's cross-setting check (gi_method_settings.check; the ldm method's also
 * checks the frame's AO maps, which are its layered depth maps): NULL or the first line. */
const char *gi_check(const frame_params *p);

/* Every option as a command-line row after the count rows in rows[CLI_MAX_OPTIONS] (base/
 * cli.h): id first_id + its index, the display settings in display_group, the rest in
 * gi_group, working in modes. Returns the new count. */
int gi_cli_options(cli_option *rows, int count, int first_id, int gi_group,
                   int display_group, unsigned modes);
/* Method m's settings from p into its struct (out: struct_size bytes). */
void gi_settings_read(int method, const frame_params *p, void *out);
/* 1 when a and b differ in a setting of method m that rebuilds it (SETTING_REBUILD). */
int gi_rebuild_needed(int method, const frame_params *a, const frame_params *b);
/* frame_params_sanitize(), then the method (an unknown one: 0) and every set slot clamped
 * by its row; returns how many fields changed. What a node does once per frame. */
int gi_frame_sanitize(frame_params *p);
/* The parameter store's schema: params_schema_init() and a key per GI option (the frame's
 * transport settings are in the core schema already). */
void gi_params_schema(params_schema *s);

#endif
