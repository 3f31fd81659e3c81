/* cluster_config: a cluster described in JSON (configs/clusters/NAME.json, docs/cluster.md).
 *
 *   master    {"bind": "tcp://0.0.0.0:5570", "connect": "tcp://host:5570"}
 *   observer  {"eye_separation": m, "head_to_eye": [x,y,z] (head space), "home": [x,y,z],
 *              "tracker_to_cave": {"translation": [..], "rotation_deg": [x,y,z], "scale": s}}
 *   screens   [{"name", "bottom_left", "bottom_right", "top_left" (CAVE space, metres),
 *               "top_right" (optional, when measured too),
 *               "overview": [x, y] (pixel offset in the unfolded overview, optional)}]
 *             Measured corners are fitted to the nearest rectangle (screen_fit.h) and
 *             refused when one moves more than "corner_tolerance_mm" (top level, 20).
 *   nodes     [{"name", "host", "screens": ["name" | {"name", "resolution", "warp"}],
 *               "resolution": [w, h], "eyes": "mono|stereo|left|right",
 *               "output": "window|headless|png", "stereo": "quad|side-by-side|top-bottom|
 *               window-per-eye|anaglyph", the window keys (cluster_window below),
 *               "exe", "workdir", "config" (the node program, its working folder and this
 *               file's path on the node's host, for --spawn-remote and scripts/
 *               install_nodes.py; default: the master's), "display" (X display for window
 *               output when DISPLAY is unset, default ":0")}]
 *   optional  "name", "scene", "app" (an application's shared object, cavelight/app.h: the
 *             master and every node load it unless --app says otherwise; the path as every
 *             host sees it), "launch" ("ssh -n {host} {command}"),
 *             "scene_transform": {"scale", "up": "y|z", "anchor": "auto|camera|centre|none",
 *                                 "fit": bool, "rotation_deg": [x,y,z], "translation":
 *                                 [x,y,z]} (scene/scene_transform.h; --scene-transform),
 *             "timeouts": {"barrier_ms", "heartbeat_ms", "master_ms", "stall_min_ms",
 *                          "join_ms"},
 *             "limits": {"gi_memory_mb"} (what a node's GI may take, common/gi/gi_cost.h),
 *             "settings": {"NAME": value, ...} (the options of cavelight-master's GI and
 *             display groups by their names, e.g. {"gi": "vpl", "vpl-interleave": 4}: the
 *             session's settings for every node, checked by the programs that know them),
 *             "security": {"mode": "curve" (default) | "insecure", "keys": DIR}
 *             (curve: every connection authenticated and encrypted with the key files
 *             in DIR, default NAME.keys beside the config; see cluster_keys.h. insecure:
 *             no authentication, for local runs and tests only)
 * Loading validates everything; a failure is one line naming the file and the field. A key
 * that no section reads (misspelt, or in the wrong place) is no failure: it is kept as a
 * line in unknown_keys, with the nearest key the section does read, for the program to
 * warn with or, when asked to be strict, refuse (base/json_keys.h: each section's valid
 * keys are the ones its parser reads). */
#ifndef CAVELIGHT_CLUSTER_CONFIG_H
#define CAVELIGHT_CLUSTER_CONFIG_H

#include <stddef.h>
#include <stdint.h>

#include "scene/scene_load.h"
#include "warp/warp_map.h"

enum { CLUSTER_GI_MEMORY_MB = 2048 };
enum {
    CLUSTER_MAX_SCREENS = 32,
    CLUSTER_MAX_NODES = 32,
    CLUSTER_NODE_MAX_SCREENS = 8,
    CLUSTER_NAME_MAX = 32,
    CLUSTER_TEXT_MAX = 256,
    CLUSTER_MAX_SETTINGS = 64,
    CLUSTER_MAX_UNKNOWN_KEYS = 16, /* lines kept; unknown_key_count counts them all */
    CLUSTER_LINE_MAX = 512,        /* one message line */
};

/* Where the master and the nodes write what they make (images, overview, report, logs,
 * recordings) unless told otherwise: relative to each program's working folder. */
#define CLUSTER_DEFAULT_OUT "out"

typedef enum cluster_eyes {
    CLUSTER_EYES_MONO = 0, /* one centre eye */
    CLUSTER_EYES_STEREO,
    CLUSTER_EYES_LEFT,
    CLUSTER_EYES_RIGHT,
} cluster_eyes;

typedef enum cluster_output {
    CLUSTER_OUTPUT_WINDOW = 0,
    CLUSTER_OUTPUT_HEADLESS, /* render, show nothing */
    CLUSTER_OUTPUT_PNG,      /* write one PNG per screen and eye on every swap */
} cluster_output;

typedef enum cluster_stereo {
    CLUSTER_STEREO_QUAD = 0,     /* quad-buffered, where the driver offers it */
    CLUSTER_STEREO_SIDE_BY_SIDE,
    CLUSTER_STEREO_TOP_BOTTOM,
    CLUSTER_STEREO_WINDOW_PER_EYE,
    CLUSTER_STEREO_ANAGLYPH,     /* red-cyan, for a desk */
} cluster_stereo;

typedef enum cluster_security {
    CLUSTER_SECURITY_CURVE = 0,  /* CurveZMQ: configured keys only, encrypted */
    CLUSTER_SECURITY_INSECURE,   /* anyone who reaches the port; local runs and tests */
} cluster_security;

/* Corners nearer a rectangle than this (1 micrometre, float rounding at CAVE sizes) are
 * kept as written. */
#define SCREEN_EXACT_M 1e-6

typedef struct cluster_screen {
    char name[CLUSTER_NAME_MAX + 1];
    float bottom_left[3], bottom_right[3], top_left[3]; /* a rectangle (fitted, see below) */
    float fit_mm;    /* how far the fit moved the furthest measured corner, millimetres */
    int overview[2]; /* pixel offset in the overview; -1 = not shown */
} cluster_screen;

/* ---- display hardware: a node's window and each screen's projector --------------------- */

/* A node's window(s) for window output, from the node's keys:
 *   "monitor": INDEX | "NAME" | [LEFT, RIGHT]  the monitor (GLFW index, or the output's
 *                  name as xrandr lists it, e.g. "DP-1"); the second is the right eye's
 *                  window under window-per-eye (default: the next index)
 *   "fullscreen": bool        cover the monitor at its current video mode
 *   "position": [x, y]        the window's top-left on the desktop, pixels (window-per-eye:
 *                             the right eye's window to the right of the left's)
 *   "size": [w, h]            the window's size (default: the images' size)
 *   "vsync": bool | n         swap every n-th refresh (true: 1, the default; false: 0)
 *   "swap_group": n, "swap_barrier": n   NVIDIA GLX_NV_swap_group: the group to join and
 *                  the barrier to bind it to (0: none); joined when the driver has the
 *                  extension, the software barrier runs in either case */
typedef struct cluster_window {
    int monitor[2];                              /* by index: left (or only), right */
    char monitor_name[2][CLUSTER_NAME_MAX + 1];  /* by name when not "" */
    int fullscreen;
    int position[2], have_position;
    int size[2];                                 /* 0 0: the images' size */
    int swap_interval;
    int swap_group, swap_barrier;
} cluster_window;

/* The window of a node that sets none of the keys: monitor 0 (the right eye's 1), vsync on. */
void cluster_window_default(cluster_window *w);

typedef enum cluster_warp_kind {
    CLUSTER_WARP_NONE = 0,
    CLUSTER_WARP_MPCDI,    /* a region of an MPCDI file (warp/mpcdi.h) */
    CLUSTER_WARP_MESH,     /* a cavelight warp mesh file (warp/warp_mesh.h) */
} cluster_warp_kind;

/* A screen's projector (a node screen's "warp": {"mpcdi": FILE, "region": ID,
 * "to_cave": {"translation", "rotation_deg", "scale"}} or {"mesh": FILE}); FILE is
 * relative to the config's folder. The node reads it once at start. */
typedef struct cluster_warp {
    cluster_warp_kind kind;
    char path[CLUSTER_TEXT_MAX];   /* resolved against the config's folder */
    char region[CLUSTER_TEXT_MAX]; /* MPCDI region id; "" = the file's only region */
    float to_cave[16];             /* MPCDI 3d: the file's points (metres) to CAVE space */
} cluster_warp;
/* A screen's projector warp read from its file (mpcdi_load() or warp_mesh_load()). Returns
 * 0 (out untouched for CLUSTER_WARP_NONE), or -1 with one line in err. */
int cluster_warp_load(const cluster_warp *w, warp_map *out, char *err, size_t errlen);

typedef struct cluster_node_screen {
    int screen;        /* index into cluster_config.screens */
    int width, height; /* pixels */
    cluster_warp warp;
} cluster_node_screen;

typedef struct cluster_node {
    char name[CLUSTER_NAME_MAX + 1];
    char host[CLUSTER_TEXT_MAX];
    int screen_count;
    cluster_node_screen screens[CLUSTER_NODE_MAX_SCREENS];
    cluster_eyes eyes;
    cluster_output output;
    cluster_stereo stereo;
    cluster_window window;
    char exe[CLUSTER_TEXT_MAX];     /* "" = the master's choice (--node-exe, or beside it) */
    char workdir[CLUSTER_TEXT_MAX]; /* "" = wherever the launch starts it */
    char config[CLUSTER_TEXT_MAX];  /* this config's path on the host; "" = the master's */
    char display[CLUSTER_TEXT_MAX]; /* window output without DISPLAY set: this one */
} cluster_node;

typedef struct cluster_observer {
    float eye_separation;   /* metres */
    float head_to_eye[3];   /* tracker sensor to the point between the eyes, head space */
    float tracker_to_cave[16]; /* column-major */
    float home[3];          /* untracked head position in CAVE space (default 0, 1.7, 0) */
} cluster_observer;

/* One entry of "settings", as text. */
typedef struct cluster_setting {
    char name[CLUSTER_NAME_MAX + 1];
    char value[64];
} cluster_setting;

typedef struct cluster_config {
    char path[CLUSTER_TEXT_MAX];
    char name[CLUSTER_TEXT_MAX];
    char scene[CLUSTER_TEXT_MAX];          /* "" = the built-in default scene */
    char app[CLUSTER_TEXT_MAX];            /* "" = no application */
    int has_scene_transform;               /* 0: the scene as modelled */
    scene_transform scene_transform;       /* "scene_transform", or --scene-transform */
    int scene_outside_paths;               /* --allow-outside-paths (never from the file) */
    char master_bind[CLUSTER_TEXT_MAX];
    char master_connect[CLUSTER_TEXT_MAX];
    char launch[CLUSTER_TEXT_MAX];         /* {host} and {command} are substituted */
    cluster_security security;
    char keys_dir[CLUSTER_TEXT_MAX];       /* curve: key folder, relative to the cwd */
    int barrier_timeout_ms;  /* a node not READY by then is dropped (default 2000) */
    int heartbeat_ms;        /* the longest either side stays silent (default 100) */
    int master_timeout_ms;   /* a node hearing nothing this long reports the master lost
                                (default 4 x heartbeat_ms) */
    int stall_min_ms;        /* floor of the adaptive stall timeout (default 250) */
    int join_timeout_ms;     /* the master waits this long for every node to join (15000) */
    double corner_tolerance_mm; /* measured corners further from a rectangle are refused (20) */
    double gi_memory_mb;     /* a node's GI state and RSMs at most (CLUSTER_GI_MEMORY_MB) */
    cluster_observer observer;
    int setting_count;
    cluster_setting settings[CLUSTER_MAX_SETTINGS];
    int screen_count;
    cluster_screen screens[CLUSTER_MAX_SCREENS];
    int node_count;
    cluster_node nodes[CLUSTER_MAX_NODES];
    uint64_t hash;           /* FNV-1a of the file bytes; HELLO carries it */
    int unknown_key_count;   /* keys no section reads */
    /* "cluster config FILE: field nodes[0].resolutoin: unknown key "resolutoin" (did you
     * mean "resolution"?)", the first CLUSTER_MAX_UNKNOWN_KEYS of them */
    char unknown_keys[CLUSTER_MAX_UNKNOWN_KEYS][CLUSTER_LINE_MAX];
} cluster_config;

/* Return 0, or -1 with "cluster config FILE: field F: problem" in err. */
int cluster_config_load(const char *path, cluster_config *out, char *err, size_t errlen);
int cluster_config_parse(const char *text, size_t len, const char *path, cluster_config *out,
                         char *err, size_t errlen);
/* A scene_transform object as JSON text (the master's and the node's --scene-transform):
 * the same rules as the config's key. 0, or -1 with "scene_transform.F: ..." in err. */
int cluster_scene_transform_parse(const char *json, scene_transform *out, char *err, size_t errlen);
/* The same for an option's value (base/cli.h's set()): NULL, or why it is refused. */
const char *cluster_scene_transform_option(const char *json, scene_transform *out);
/* How every program of this cluster loads its scene: the transform, the stage (the
 * observer's home, the box of every screen's corners) and the path rule. */
void cluster_config_scene_desc(const cluster_config *c, scene_load_desc *out);
/* Index of the node or screen with this name, or -1. */
int cluster_config_find_node(const cluster_config *c, const char *name);
int cluster_config_find_screen(const cluster_config *c, const char *name);
const char *cluster_eyes_name(cluster_eyes e);
const char *cluster_output_name(cluster_output o);
const char *cluster_stereo_name(cluster_stereo s);
const char *cluster_security_name(cluster_security s);
/* Parse names as in the file; return -1 when unknown. */
int cluster_output_parse(const char *s);
int cluster_stereo_parse(const char *s);

#endif
