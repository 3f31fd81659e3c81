/* scene: the scene model every node loads for itself.
 *
 * Meshes are flattened to world-space triangles (3 vertices each, no index buffer) with
 * per-vertex unit normals and uvs and one material index per triangle. Materials carry a
 * linear base colour factor, an optional base colour texture (RGBA8, sRGB-encoded as in
 * glTF) and emitted radiance (emissive surfaces are surface lights). Lights are spots,
 * point lights or directional lights (glTF's KHR_lights_punctual); cameras are the file's.
 *
 * scene_load() (scene_load.c; scene_load.h places the scene too) picks the loader: a
 * built-in scene's name (scene_builtin_name(): the chart's rooms in scene_default.c,
 * scene_corridor.c, scene_doorway.c, scene_courtyard.c, scene_arcades.c, the open street
 * block of scene_street.c and the leak tests' boxes in scene_leaks.c) builds it in code,
 * *.gltf / *.glb go through tinygltf (gltf_import.cpp).
 * The scene owns its arrays; scene_free() releases them. The scene_add_* builders are what
 * the loaders use. */
#ifndef CAVELIGHT_SCENE_H
#define CAVELIGHT_SCENE_H

#include <stddef.h>
#include <stdint.h>

enum { SCENE_MAX_LIGHTS = 8 };
/* Movable parts (scene_object): at most this many per scene, each named in at most
 * SCENE_NAME_MAX - 1 bytes (a parameter-store key each, cluster/scene_keys.h). */
enum { SCENE_MAX_OBJECTS = 128, SCENE_NAME_MAX = 48 };
/* No vertex or light farther than this from the origin on any axis, metres (100 km): the
 * counts that follow from the extent (light cache points, lookup cells) stay bounded and
 * float positions keep millimetres. */
#define SCENE_MAX_COORD 1.0e5f

typedef struct scene_material {
    float base_color[4];    /* linear RGBA factor */
    int base_color_texture; /* index into textures, -1 = none */
    float emissive[3];      /* emitted radiance, linear RGB, W/(sr m^2) */
    float roughness;        /* [0,1], glTF roughnessFactor */
} scene_material;

typedef struct scene_texture {
    int width, height;
    uint8_t *rgba;          /* width*height*4, first row first, sRGB-encoded */
} scene_texture;

/* Spot is 0, so a zeroed light is a spot. */
typedef enum scene_light_type {
    SCENE_LIGHT_SPOT = 0,        /* from position into a cone around direction */
    SCENE_LIGHT_POINT = 1,       /* from position in every direction */
    SCENE_LIGHT_DIRECTIONAL = 2, /* parallel, along direction, from outside the scene */
    SCENE_LIGHT_TYPES
} scene_light_type;

/* Units (one rule for every light): glTF's photometric units are taken 1:1 as radiometric
 * ones in our linear units, 1 cd = 1 W/sr and 1 lx = 1 W/m^2 (1 cd at 1 m gives 1 lx, and
 * 1 W/sr at 1 m gives 1 W/m^2, so the rule keeps the file's lights in proportion). */
typedef struct scene_light {
    float position[3];      /* spot, point; directional: where the file put it (HUD only) */
    float direction[3];     /* unit: spot axis, direction a directional light travels */
    float color[3];         /* linear RGB */
    float intensity;        /* spot, point: radiant intensity, W/sr (glTF candela);
                               directional: irradiance on a surface facing it, W/m^2 (lux) */
    float outer_angle;      /* spot: half angle, radians */
    float inner_angle;
    scene_light_type type;
} scene_light;

typedef struct scene_camera {
    int valid;
    float position[3], target[3];
    float yfov;             /* radians (perspective) */
    float up[3];            /* the camera's up; zero: +y (+z when looking straight up/down) */
    int orthographic;       /* glTF orthographic: ymag instead of yfov */
    float ymag;             /* orthographic: half height of the view, metres */
    float aspect;           /* width / height the file asks for, 0 = the image's */
    float znear, zfar;      /* clip distances, 0 = the node's defaults */
    char name[64];          /* the glTF node's name, else the camera's, else "" */
    char camera_name[64];   /* the glTF camera's own name */
} scene_camera;

/* A part of the scene that can move (scene_pose.h): a glTF node whose subtree holds
 * triangles, or a built-in scene's named part. Its own triangles are those whose
 * triangle_object is its index; it moves with its parent. */
typedef struct scene_object {
    char name[SCENE_NAME_MAX];  /* the node's name (printable ASCII), "nodeN" when it has
                                   none, "NAME#2" for a second node of that name */
    int parent;                 /* object index, -1: none */
    /* The node's own transform as loaded, in the file's space, for its animations:
     * translation, rotation (unit quaternion x, y, z, w), scale; rest_world is the node's
     * world matrix in the file's space (column-major). Identity for built-in parts. */
    float rest_translation[3], rest_rotation[4], rest_scale[3];
    float rest_world[16];
} scene_object;

/* One glTF animation channel: keyframes of an object's translation, rotation or scale,
 * played by the master's clock (scene_pose_animate()). */
typedef enum scene_anim_path {
    SCENE_ANIM_TRANSLATION = 0,
    SCENE_ANIM_ROTATION,
    SCENE_ANIM_SCALE,
} scene_anim_path;

typedef struct scene_anim_channel {
    int object;
    scene_anim_path path;
    int step;                   /* 1: STEP (hold each key), 0: linear (slerp for rotations) */
    size_t count;               /* keyframes, times increasing */
    float *times;               /* seconds */
    float *values;              /* 3 floats a key (4 for a rotation) */
} scene_anim_channel;

typedef struct scene {
    size_t triangle_count;
    float *positions;       /* 9 floats per triangle */
    float *normals;         /* 9 floats per triangle, unit */
    float *uvs;             /* 6 floats per triangle */
    uint32_t *triangle_material;
    int32_t *triangle_object;   /* per triangle: its object, -1 static (NULL: all static) */
    size_t triangle_capacity;
    int object_count;
    scene_object *objects;
    int adding_object;          /* scene_add_triangle()'s object + 1, 0: static (set by
                                   scene_begin_object(), scene_end_object()) */
    size_t anim_channel_count;
    scene_anim_channel *anim_channels;
    float anim_duration;        /* the longest channel's last key time: the loop */
    int placed;                 /* 1: placement holds scene_transform_apply()'s matrix */
    float placement[16];        /* file space to the scene's (column-major) */
    size_t material_count;
    scene_material *materials;
    size_t texture_count;
    scene_texture *textures;
    int light_count;
    scene_light lights[SCENE_MAX_LIGHTS];
    int light_added;        /* 1: the file had no light (and no emitter), so scene_load()
                               added lights[0] inside the bounds (scene_default_light()) */
    scene_camera camera;    /* the view to use: the file's first camera, or a built-in
                               scene's; scene_pick_camera() chooses another */
    size_t camera_count;    /* the file's cameras, in the order the scene graph lists them */
    scene_camera *cameras;
    float bounds_min[3], bounds_max[3]; /* valid after scene_finish() */
    char warning[512];      /* what the file asks for and the scene draws differently
                               (materials, ignored extensions), one line; "" if nothing */
} scene;

/* A built-in scene's name or a .gltf/.glb path, as modelled: scene_load_with() (scene_load.h)
 * with no transform. Returns 0, or -1 with one line in err (and *out empty). A scene with
 * neither lights nor emissive surfaces gets scene_default_light() and light_added = 1 (the
 * caller says so to the user: scene_light_added_note()). */
int scene_load(const char *path, scene *out, char *err, size_t errlen);
/* The i-th built-in scene's name ("default", "corridor", ...), NULL past the last. */
const char *scene_builtin_name(int i);
void scene_free(scene *s);

/* Builders. Each returns the new index (>= 0) or -1 when out of memory. */
int scene_add_material(scene *s, const scene_material *m);
/* Takes ownership of rgba (malloc'ed, width*height*4). */
int scene_add_texture(scene *s, int width, int height, uint8_t *rgba);
/* normals: 9 floats or NULL for the face normal; uvs: 6 floats or NULL for zeros. */
long scene_add_triangle(scene *s, const float positions[9], const float *normals,
                        const float *uvs, uint32_t material);
/* A single-sided, zero-thickness quad abcd (triangles abc, acd) with normal n at every
 * vertex and uvs from 0 to 1, as glTF exporters write walls. */
int scene_add_quad(scene *s, const float a[3], const float b[3], const float c[3],
                   const float d[3], const float n[3], uint32_t material);
/* An axis-aligned, zero-thickness rectangle from lo to hi (equal on exactly one axis), its
 * normal along that axis, positive if facing > 0; -1 if it is not flat or facing is 0. */
int scene_add_rect(scene *s, const float lo[3], const float hi[3], int facing,
                   uint32_t material);
/* Appends an axis-aligned box with outward (or inward, for a room) faces: six rectangles. */
int scene_add_box(scene *s, const float min[3], const float max[3], int inward, uint32_t material);
int scene_add_light(scene *s, const scene_light *l);
/* A new object (name as given: made printable, cut to SCENE_NAME_MAX - 1, made unique),
 * and the object the next triangles belong to. Returns its index, or -1 when there are
 * SCENE_MAX_OBJECTS already (the triangles then stay static) or out of memory. */
int scene_begin_object(scene *s, const char *name, int parent);
/* The next triangles are static (or parent's: scene_begin_object()'s again). */
void scene_end_object(scene *s, int object);
/* The object named name, or -1. */
int scene_object_find(const scene *s, const char *name);
/* Adds a channel (takes ownership of times and values, malloc'ed). -1 when out of memory. */
int scene_add_anim_channel(scene *s, const scene_anim_channel *c);
/* Points the light's axis from its position at target (unchanged if they coincide). */
void scene_light_aim(scene_light *l, const float target[3]);
/* Computes the bounds; returns -1 with a reason when the scene has no triangles, or a vertex
 * or light is not finite or lies beyond SCENE_MAX_COORD. */
int scene_finish(scene *s, char *err, size_t errlen);

/* 1 when some triangle's material emits light. */
int scene_has_emitter(const scene *s);
/* Length of the bounds' diagonal. Needs scene_finish(). */
float scene_diagonal(const scene *s);
/* Inverse-square falloff is bounded at this distance from a light (diagonal / 64: 10 cm in
 * the default room), so irradiance stays finite next to it; the rasterizer and the
 * path-traced reference share it. */
float scene_min_light_distance(const scene *s);
/* Far clip distance that keeps the whole scene visible from in or near its bounds:
 * 4 x the bounds' diagonal + 10 m. Needs scene_finish(). */
float scene_far_plane(const scene *s);
/* Where to look from when nothing else says (scene_place.c). The scene's own camera if it
 * has one. Else from inside, when the scene is a room: at eye height (min(1.6 m, half the
 * height) above the floor of the bounds) at the first free point (scene_point_is_free())
 * of 10%, 25%, 40% along the longest horizontal extent (middle, then 30% and 70% across),
 * looking along that axis, if most rays from there meet the front of a surface. Else (an
 * object seen from outside) at the bounds' centre from +0.3 x the largest extent up and
 * +1.5 x towards +z; a flat object (its thinnest extent under a tenth of the largest) from
 * 1.5 x along its thin axis on the side its surfaces face, 0.3 x askew. Needs
 * scene_finish(). */
void scene_default_view(const scene *s, float position[3], float target[3]);
/* The camera to look through when nothing else says: the scene's own (a file's first, or
 * the one scene_pick_camera() chose), else a 60 degree perspective camera at
 * scene_default_view(). */
void scene_default_camera(const scene *s, scene_camera *out);
/* The light scene_load() gives a scene without lights or emitters: a white point light.
 * When the default camera (scene_default_camera()) stands in a room (free, and most probe
 * rays meet the front of a surface), inside the bounds three quarters of the way up over
 * the middle (a ceiling lamp), moved to the first point of a grid over the bounds that is
 * free and D/16 from every surface the probes meet (D the bounds' diagonal) when that spot
 * is not; its intensity gives 2 W/m^2 on the floor of the bounds straight below. Else (an
 * object seen from outside) above the camera by a quarter of its distance to the bounds'
 * middle and at least D/16 outside the bounds (never inside the model or in the plane of a
 * flat one), giving 2 W/m^2 at the middle. */
void scene_default_light(const scene *s, scene_light *out);
/* 1 when p is outside every closed solid as far as 14 rays from p can tell: no ray's first
 * hit is the back of a surface (the side its vertex normals turn away from). *fronts (if
 * not NULL) counts the rays whose first hit is the front of a surface. Brute force over
 * the triangles. */
int scene_point_is_free(const scene *s, const float p[3], int *fronts);
/* The one line that tells a user about the added light, e.g. "scene room.gltf has no
 * lights: added a point light at (0, 2.25, 0), 10.1 W/sr, inside its bounds (add a
 * KHR_lights_punctual light to choose your own)" ("outside its bounds on its camera's
 * side" for an object). */
void scene_light_added_note(const scene *s, const char *path, char *out, size_t n);
/* The line a user needs about the scene's light, and 1: the added light's note, or for a
 * scene with emissive surfaces and no light "scene X: only emissive materials and no light:
 * ..."; 0 (out untouched) when the scene has its own lights. */
int scene_light_note(const scene *s, const char *path, char *out, size_t n);

/* Adds a copy of c to cameras. Returns its index or -1 when out of memory. */
int scene_add_camera(scene *s, const scene_camera *c);
/* Makes a file camera the scene's camera: `which` is a camera's name (its node's or its
 * own) or its index in cameras. Returns 0, or -1 with one line naming the cameras there
 * are. */
int scene_pick_camera(scene *s, const char *which, char *err, size_t errlen);

/* Built-in room: 4 x 3 x 4 m, red left wall, green right wall, white rest, two boxes,
 * a small emissive panel and one spotlight. Needs no files. */
int scene_default_build(scene *s, char *err, size_t errlen);
/* Built-in corridor: 12 x 2.6 x 2.4 m, a spot at the near end, pillars, the far end lit
 * only indirectly (scene_corridor.c). */
int scene_corridor_build(scene *s, char *err, size_t errlen);
/* Built-in pair of rooms joined by a doorway; the spot lights the first, the second is lit
 * only indirectly (scene_doorway.c). */
int scene_doorway_build(scene *s, char *err, size_t errlen);
/* Built-in open-top courtyard with tall walls, lit from above (scene_courtyard.c). */
int scene_courtyard_build(scene *s, char *err, size_t errlen);
/* Built-in 12 x 24 m courtyard with two storeys of arcaded galleries, lit by a lamp inside
 * one lower gallery (scene_arcades.c). */
int scene_arcades_build(scene *s, char *err, size_t errlen);
/* Built-in street block: an open square among buildings, 48 m across, a low sun, coloured
 * panels (scene_street.c). */
int scene_street_build(scene *s, char *err, size_t errlen);
/* Leak tests of single-sided, zero-thickness walls (scene_leaks.c; docs/stability.md):
 * a spot above a closed box with a zero-thickness lid, an emissive panel flush with the
 * ceiling of a closed room, a single-sided wall between a lit and a dark room. */
int scene_leak_lid_build(scene *s, char *err, size_t errlen);
int scene_leak_panel_build(scene *s, char *err, size_t errlen);
int scene_leak_wall_build(scene *s, char *err, size_t errlen);
/* glTF 2.0 via tinygltf (gltf_import.cpp). Buffers and images only from the file's folder
 * or below (and data: URIs) unless allow_outside_paths. Sets out->warning. */
int gltf_import(const char *path, int allow_outside_paths, scene *out, char *err, size_t errlen);

#endif
