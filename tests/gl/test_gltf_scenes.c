/* glTF scenes as users export them, written by the test: a closed room with a camera and
 * only a point light, an open courtyard with a camera and only a directional light, and a
 * closed room with neither lights nor a camera. Each renders lit from the file's camera
 * (or the default view inside the room) in the rasterizer and in the path-traced reference,
 * and the two direct images agree (as tests/gl/test_reference.c measures them). A view
 * that receives no light says so. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "cluster/cluster_config.h"
#include "gl/gl_testutil.h"
#include "image/image.h"
#include "reference/reference.h"

enum { W = 128, H = 96 };

/* ---- a small glTF writer: meshes of quads, one material each, nodes with matrices ---- */

typedef struct mesh_out {
    float *pos, *nrm, *uv;
    int vertices;
    float color[3];
} mesh_out;

/* Two triangles, the quad's uvs running 0..1 from its first corner. */
static void add_quad(mesh_out *m, const float c[4][3], const float n[3])
{
    static const int corner[6] = {0, 1, 2, 0, 2, 3};
    static const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m->pos = realloc(m->pos, (size_t)(m->vertices + 6) * 3 * sizeof(float));
    m->nrm = realloc(m->nrm, (size_t)(m->vertices + 6) * 3 * sizeof(float));
    m->uv = realloc(m->uv, (size_t)(m->vertices + 6) * 2 * sizeof(float));
    assert_true(m->pos && m->nrm && m->uv);
    for (int k = 0; k < 6; k++) {
        memcpy(m->pos + 3 * (m->vertices + k), c[corner[k]], 3 * sizeof(float));
        memcpy(m->nrm + 3 * (m->vertices + k), n, 3 * sizeof(float));
        memcpy(m->uv + 2 * (m->vertices + k), uv[corner[k]], 2 * sizeof(float));
    }
    m->vertices += 6;
}

/* The faces of the box lo..hi facing in (a room) or out (a block); bit axis * 2 + side of
 * skip leaves that face out. */
static void add_box(mesh_out *m, const float lo[3], const float hi[3], int inward, int skip)
{
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            if (skip & (1 << (axis * 2 + side)))
                continue;
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            float c[4][3], n[3] = {0, 0, 0};
            const float us[4] = {0, 1, 1, 0}, vs[4] = {0, 0, 1, 1};
            for (int k = 0; k < 4; k++) {
                c[k][axis] = side ? hi[axis] : lo[axis];
                c[k][u] = us[k] ? hi[u] : lo[u];
                c[k][v] = vs[k] ? hi[v] : lo[v];
            }
            n[axis] = (side ? 1.0f : -1.0f) * (inward ? -1.0f : 1.0f);
            add_quad(m, c, n);
        }
}

/* Column-major node matrix whose -Z axis points along forward (unit) and +Y up, at t. */
static void node_matrix(const float t[3], const float forward[3], float m[16])
{
    float up[3] = {0, 1, 0}, r[3], u[3];
    if (fabsf(forward[1]) > 0.99f)
        up[1] = 0, up[2] = 1;
    r[0] = forward[1] * up[2] - forward[2] * up[1];
    r[1] = forward[2] * up[0] - forward[0] * up[2];
    r[2] = forward[0] * up[1] - forward[1] * up[0];
    float len = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++)
        r[k] /= len;
    u[0] = r[1] * forward[2] - r[2] * forward[1];
    u[1] = r[2] * forward[0] - r[0] * forward[2];
    u[2] = r[0] * forward[1] - r[1] * forward[0];
    for (int k = 0; k < 3; k++) {
        m[k] = r[k];
        m[4 + k] = u[k];
        m[8 + k] = -forward[k];
        m[12 + k] = t[k];
    }
    m[3] = m[7] = m[11] = 0;
    m[15] = 1;
}

static void print_matrix(FILE *f, const float m[16])
{
    fprintf(f, "\"matrix\":[");
    for (int i = 0; i < 16; i++)
        fprintf(f, "%s%.9g", i ? "," : "", m[i]);
    fprintf(f, "]");
}

typedef struct gltf_out {
    mesh_out mesh[3];
    int meshes;
    const char *light;        /* KHR_lights_punctual light JSON, or NULL */
    float light_matrix[16];
    int camera;               /* 1: a camera named "Main" on node "CamNode" */
    int orthographic;         /* the camera is orthographic, 2.4 x 1.8 m */
    float camera_matrix[16];
    const char *texture;      /* a PNG beside the file for mesh 0's material, or NULL */
} gltf_out;

/* Writes path (.gltf) and path.bin. */
static void write_gltf(const char *path, gltf_out *g)
{
    char bin[512];
    snprintf(bin, sizeof bin, "%s.bin", path);
    FILE *fb = fopen(bin, "wb");
    assert_non_null(fb);
    size_t offset[3][3], length[3][3], total = 0;
    for (int i = 0; i < g->meshes; i++)
        for (int a = 0; a < 3; a++) {
            const float *data = a == 0 ? g->mesh[i].pos : a == 1 ? g->mesh[i].nrm : g->mesh[i].uv;
            length[i][a] = (size_t)g->mesh[i].vertices * (a == 2 ? 2 : 3) * sizeof(float);
            offset[i][a] = total;
            assert_int_equal(fwrite(data, 1, length[i][a], fb), length[i][a]);
            total += length[i][a];
        }
    fclose(fb);
    const char *slash = strrchr(bin, '/');
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[");
    int nodes = g->meshes + (g->light != NULL) + g->camera;
    for (int i = 0; i < nodes; i++)
        fprintf(f, "%s%d", i ? "," : "", i);
    fprintf(f, "]}],\"nodes\":[");
    for (int i = 0; i < g->meshes; i++)
        fprintf(f, "%s{\"mesh\":%d}", i ? "," : "", i);
    if (g->light) {
        fprintf(f, ",{\"name\":\"Lamp\",");
        print_matrix(f, g->light_matrix);
        fprintf(f, ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}");
    }
    if (g->camera) {
        fprintf(f, ",{\"name\":\"CamNode\",\"camera\":0,");
        print_matrix(f, g->camera_matrix);
        if (g->orthographic)
            fprintf(f, "}],\"cameras\":[{\"name\":\"Main\",\"type\":\"orthographic\","
                       "\"orthographic\":{\"xmag\":2.4,\"ymag\":1.8,\"znear\":0.01,\"zfar\":20}}");
        else
            fprintf(f, "}],\"cameras\":[{\"name\":\"Main\",\"type\":\"perspective\",\"perspective\":"
                       "{\"yfov\":1.0,\"znear\":0.05,\"aspectRatio\":%.9g}}", (double)W / H);
    }
    fprintf(f, "]");
    if (g->light)
        fprintf(f, ",\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":"
                   "{\"KHR_lights_punctual\":{\"lights\":[%s]}}", g->light);
    fprintf(f, ",\"meshes\":[");
    for (int i = 0; i < g->meshes; i++)
        fprintf(f, "%s{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d},"
                   "\"material\":%d}]}", i ? "," : "", 3 * i, 3 * i + 1, 3 * i + 2, i);
    fprintf(f, "],\"materials\":[");
    for (int i = 0; i < g->meshes; i++)
        fprintf(f, "%s{\"pbrMetallicRoughness\":{\"baseColorFactor\":[%g,%g,%g,1],"
                   "\"metallicFactor\":0,\"roughnessFactor\":0.8%s}}", i ? "," : "",
                g->mesh[i].color[0], g->mesh[i].color[1], g->mesh[i].color[2],
                i == 0 && g->texture ? ",\"baseColorTexture\":{\"index\":0}" : "");
    if (g->texture)
        fprintf(f, "],\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"%s\"}", g->texture);
    fprintf(f, "],\"accessors\":[");
    for (int i = 0; i < 3 * g->meshes; i++)
        fprintf(f, "%s{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"%s\"}",
                i ? "," : "", i, g->mesh[i / 3].vertices, i % 3 == 2 ? "VEC2" : "VEC3");
    fprintf(f, "],\"bufferViews\":[");
    for (int i = 0; i < 3 * g->meshes; i++)
        fprintf(f, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", i ? "," : "",
                offset[i / 3][i % 3], length[i / 3][i % 3]);
    fprintf(f, "],\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}]}\n", total, slash + 1);
    fclose(f);
    for (int i = 0; i < g->meshes; i++) {
        free(g->mesh[i].pos);
        free(g->mesh[i].nrm);
        free(g->mesh[i].uv);
    }
}

/* A 4 x 3 x 4 m room (floor reddish, the rest light grey) with a blue block; open: no
 * ceiling. */
static void room(gltf_out *g, int open)
{
    memset(g, 0, sizeof *g);
    const float lo[3] = {-2, 0, -2}, hi[3] = {2, 3, 2};
    const float blo[3] = {-0.9f, 0, -0.6f}, bhi[3] = {-0.1f, 1, 0.2f};
    add_box(&g->mesh[0], lo, hi, 1, 1 << 2 | (open ? 1 << 3 : 0)); /* the floor apart */
    const float floor[4][3] = {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}};
    add_quad(&g->mesh[1], floor, (const float[3]){0, 1, 0});
    add_box(&g->mesh[2], blo, bhi, 0, 0);
    memcpy(g->mesh[0].color, (const float[3]){0.8f, 0.8f, 0.78f}, sizeof g->mesh[0].color);
    memcpy(g->mesh[1].color, (const float[3]){0.7f, 0.3f, 0.3f}, sizeof g->mesh[1].color);
    memcpy(g->mesh[2].color, (const float[3]){0.3f, 0.5f, 0.8f}, sizeof g->mesh[2].color);
    g->meshes = 3;
}

static void camera_at(gltf_out *g, const float eye[3], const float target[3])
{
    float f[3], len = 0;
    for (int k = 0; k < 3; k++) {
        f[k] = target[k] - eye[k];
        len += f[k] * f[k];
    }
    for (int k = 0; k < 3; k++)
        f[k] /= sqrtf(len);
    node_matrix(eye, f, g->camera_matrix);
    g->camera = 1;
}

/* ---- rendering and comparing --------------------------------------------------------- */

typedef struct rendered {
    float *direct, *ref_direct;
    int lit;
    double mean, rel, rel_all, kept;
} rendered;

/* One rasterizer frame and the reference's exact direct light from the scene's camera. */
static void render(const scene *s, const frame_params *p, rendered *out)
{
    gltest t;
    memset(&t, 0, sizeof t);
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    assert_non_null(t.ctx = glctx_create(&gd, err, sizeof err));
    frame_params q = *p;
    gltest_setn(&q, "rsm", 256);
    gltest_setn(&q, "lattice", 16);
    gltest_set(&q, "lpv", "cpu");
    renderer_desc rd = {.gl = glctx_gl(t.ctx), .scene = s, .first = &q};
    assert_non_null(t.r = renderer_create(&rd, err, sizeof err));
    renderer_view v;
    assert_int_equal(frame_view_scene_camera(&s->camera, s->camera.position, scene_far_plane(s),
                                             W, H, &v), 0);
    renderer_frame_pass(t.r, &q);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t.r, &v, 1, &img), 0);
    size_t bytes = (size_t)W * H * 3 * sizeof(float);
    out->direct = malloc(bytes);
    assert_non_null(out->direct);
    memcpy(out->direct, img.direct, bytes);
    out->lit = img.lit;
    renderer_destroy(t.r);
    glctx_destroy(t.ctx);

    reference *ref = reference_create(s, 0, err, sizeof err);
    assert_non_null(ref);
    reference_render_desc d = {.params = p, .view = &v, .samples = 1, .max_bounces = 1};
    reference_images ri;
    assert_int_equal(reference_render(ref, &d, &ri, err, sizeof err), 0);
    out->ref_direct = ri.direct;
    free(ri.indirect1);
    free(ri.indirect);
    free(ri.coverage);
    reference_destroy(ref);
}

/* Mean |raster - reference| of the direct images relative to the reference's mean, over
 * the pixels away from a strong change in either image (shadow and geometry edges, where
 * PCF and one-sample rasterization differ) and over all pixels; the share of lit pixels. */
static double compare(rendered *r, const char *what)
{
    const float *a = r->direct, *b = r->ref_direct;
    double mean = 0, sum = 0, sum_all = 0;
    size_t kept = 0, lit = 0;
    for (size_t i = 0; i < (size_t)W * H * 3; i++)
        mean += b[i] / (3.0 * W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = ((size_t)y * W + x) * 3;
            double d = 0;
            for (int c = 0; c < 3; c++)
                d += fabs((double)a[i + c] - b[i + c]) / 3;
            sum_all += d;
            lit += b[i] + b[i + 1] + b[i + 2] > 0;
            int edge = 0;
            for (int dy = -2; dy <= 2 && !edge; dy++)
                for (int dx = -2; dx <= 2 && !edge; dx++) {
                    int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= W || ny >= H)
                        continue;
                    size_t j = ((size_t)ny * W + nx) * 3;
                    for (int c = 0; c < 3; c++) {
                        double lim = 0.15 * fmax(fabs(b[i + c]), 0.1 * mean);
                        edge |= fabs((double)a[j + c] - a[i + c]) > lim ||
                                fabs((double)b[j + c] - b[i + c]) > lim;
                    }
                }
            if (!edge) {
                sum += d;
                kept++;
            }
        }
    r->mean = mean;
    r->rel = sum / (double)(kept ? kept : 1) / mean;
    r->rel_all = sum_all / ((double)W * H) / mean;
    r->kept = (double)kept / ((double)W * H);
    double lit_share = (double)lit / ((double)W * H);
    printf("%s: direct mean %.4f, %.0f%% of the pixels lit; |raster - reference| %.3f%% of the "
           "mean on %.0f%% of the pixels (%.3f%% over all)\n", what, mean, 100 * lit_share,
           100 * r->rel, 100 * r->kept, 100 * r->rel_all);
    free(r->direct);
    free(r->ref_direct);
    return lit_share;
}

static void load(const char *path, scene *s, frame_params *p)
{
    char err[512];
    assert_int_equal(scene_load(path, s, err, sizeof err), 0);
    frame_params_default(p);
    frame_params_lights_from_scene(p, s);
}

#define TMP CAVELIGHT_BINARY_DIR "/test_gltf_scenes_"

/* A closed room, a camera and only a point light: the file's camera and light are used,
 * the room is lit from it, rasterizer and reference agree. Measured (RSM 256, llvmpipe):
 * see docs/reference.md. */
static void test_point_light_room(void **state)
{
    (void)state;
    gltf_out g;
    room(&g, 0);
    g.light = "{\"type\":\"point\",\"intensity\":8,\"color\":[1,0.95,0.9]}";
    node_matrix((const float[3]){0.4f, 2.3f, 0.3f}, (const float[3]){0, -1, 0}, g.light_matrix);
    camera_at(&g, (const float[3]){1.5f, 1.6f, 1.7f}, (const float[3]){-0.5f, 0.8f, -1.2f});
    write_gltf(TMP "point.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "point.gltf", &s, &p);
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.lights[0].type, SCENE_LIGHT_POINT);
    assert_false(s.light_added);
    assert_true(fabsf(s.lights[0].position[1] - 2.3f) < 1e-6f && s.lights[0].intensity == 8.0f);
    assert_int_equal(s.camera_count, 1);
    assert_true(s.camera.valid && strcmp(s.camera.name, "CamNode") == 0 &&
                strcmp(s.camera.camera_name, "Main") == 0);
    assert_true(fabsf(s.camera.position[0] - 1.5f) < 1e-5f && fabsf(s.camera.yfov - 1.0f) < 1e-6f);
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "point light, file camera");
    assert_true(lit > 0.9);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* The same room through an orthographic camera standing inside it: its window reaches past
 * the side walls, whose outsides it sees (unlit: shading takes the view's direction, not
 * the camera's position, for the side a surface shows). */
static void test_orthographic_camera(void **state)
{
    (void)state;
    gltf_out g;
    room(&g, 0);
    g.light = "{\"type\":\"point\",\"intensity\":8}";
    node_matrix((const float[3]){0.4f, 2.3f, 0.3f}, (const float[3]){0, -1, 0}, g.light_matrix);
    camera_at(&g, (const float[3]){1.5f, 1.6f, 1.7f}, (const float[3]){-0.5f, 0.8f, -1.2f});
    g.orthographic = 1;
    write_gltf(TMP "ortho.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "ortho.gltf", &s, &p);
    assert_true(s.camera.orthographic && s.camera.ymag == 1.8f);
    assert_true(fabsf(s.camera.aspect - 2.4f / 1.8f) < 1e-6f);
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "point light, orthographic file camera");
    assert_true(lit > 0.1 && lit < 0.5);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* An open courtyard (no ceiling), a camera and only a directional light from above at a
 * slant: lit from the file's camera with the walls' and the block's shadows, rasterizer
 * and reference agree. */
static void test_directional_courtyard(void **state)
{
    (void)state;
    gltf_out g;
    room(&g, 1);
    g.light = "{\"type\":\"directional\",\"intensity\":3}";
    float d[3] = {0.5f, -1.0f, -0.35f}, len = sqrtf(0.25f + 1.0f + 0.35f * 0.35f);
    for (int k = 0; k < 3; k++)
        d[k] /= len;
    node_matrix((const float[3]){0, 5, 0}, d, g.light_matrix);
    camera_at(&g, (const float[3]){1.5f, 1.6f, 1.7f}, (const float[3]){-0.5f, 0.8f, -1.2f});
    write_gltf(TMP "sun.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "sun.gltf", &s, &p);
    assert_int_equal(s.lights[0].type, SCENE_LIGHT_DIRECTIONAL);
    for (int k = 0; k < 3; k++)
        assert_true(fabsf(s.lights[0].direction[k] - d[k]) < 1e-5f);
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "directional light, file camera");
    assert_true(lit > 0.4);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* A closed room without lights or camera: scene_load() adds a point light inside it and
 * says so (light_added); the default view is inside too, and everything it sees is lit
 * (the former spot above the scene lit only the ceiling's top, outside). */
static void test_closed_room_without_lights(void **state)
{
    (void)state;
    gltf_out g;
    room(&g, 0);
    write_gltf(TMP "dark.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "dark.gltf", &s, &p);
    assert_true(s.light_added);
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.lights[0].type, SCENE_LIGHT_POINT);
    assert_false(s.camera.valid);
    scene_camera view = {.valid = 1, .yfov = 1.0f};
    scene_default_view(&s, view.position, view.target);
    s.camera = view;
    for (int a = 0; a < 3; a++) {
        assert_true(s.lights[0].position[a] > s.bounds_min[a] && s.lights[0].position[a] < s.bounds_max[a]);
        assert_true(s.camera.position[a] > s.bounds_min[a] && s.camera.position[a] < s.bounds_max[a]);
    }
    char note[400];
    scene_light_added_note(&s, "dark.gltf", note, sizeof note);
    assert_non_null(strstr(note, "dark.gltf has no lights: added a point light"));
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "closed room without lights, default view and light");
    assert_true(lit > 0.9);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* Neither lights nor a camera, as CAD and scan exports often come. Sets up the default
 * view (the file has no camera) and checks the added light is outside the bounds: for an
 * object it stands on the camera's side, never inside the model or in a flat one's plane. */
static void default_view_and_light(scene *s)
{
    assert_true(s->light_added);
    assert_false(s->camera.valid);
    scene_camera view = {.valid = 1, .yfov = 1.0f};
    scene_default_view(s, view.position, view.target);
    s->camera = view;
    int outside_view = 0, outside_light = 0;
    for (int a = 0; a < 3; a++) {
        outside_view |= view.position[a] < s->bounds_min[a] || view.position[a] > s->bounds_max[a];
        outside_light |= s->lights[0].position[a] < s->bounds_min[a] - scene_diagonal(s) / 16 ||
                         s->lights[0].position[a] > s->bounds_max[a] + scene_diagonal(s) / 16;
    }
    assert_true(outside_view && outside_light);
}

/* A flat model (one single-sided 2 x 2 m panel facing +y): seen from the side it faces and
 * lit from there. The former automatic light sat in its plane and left it black. */
static void test_flat_model(void **state)
{
    (void)state;
    gltf_out g;
    memset(&g, 0, sizeof g);
    const float c[4][3] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    add_quad(&g.mesh[0], c, (const float[3]){0, 1, 0});
    memcpy(g.mesh[0].color, (const float[3]){0.7f, 0.7f, 0.7f}, sizeof g.mesh[0].color);
    g.meshes = 1;
    write_gltf(TMP "flat.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "flat.gltf", &s, &p);
    default_view_and_light(&s);
    assert_true(s.camera.position[1] > 1 && s.lights[0].position[1] > 1);
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "flat panel without lights or camera");
    assert_true(lit > 0.2);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* A closed, textured 1 m box (faces out), no lights or camera: seen from outside, lit. */
static void test_textured_box(void **state)
{
    (void)state;
    const uint8_t rgb[4 * 3] = {200, 40, 40, 40, 200, 40, 40, 40, 200, 220, 220, 220};
    char err[256];
    assert_int_equal(image_write_png(TMP "box.png", 2, 2, rgb, err, sizeof err), 0);
    gltf_out g;
    memset(&g, 0, sizeof g);
    add_box(&g.mesh[0], (const float[3]){-0.5f, -0.5f, -0.5f}, (const float[3]){0.5f, 0.5f, 0.5f}, 0, 0);
    memcpy(g.mesh[0].color, (const float[3]){1, 1, 1}, sizeof g.mesh[0].color);
    g.meshes = 1;
    g.texture = "test_gltf_scenes_box.png";
    write_gltf(TMP "box.gltf", &g);
    scene s;
    frame_params p;
    load(TMP "box.gltf", &s, &p);
    assert_int_equal(s.texture_count, 1);
    default_view_and_light(&s);
    rendered r;
    render(&s, &p, &r);
    assert_true(r.lit);
    double lit = compare(&r, "textured box without lights or camera");
    assert_true(lit > 0.1);
    assert_true(r.kept > 0.5 && r.rel < 0.005 && r.rel_all < 0.02);
    scene_free(&s);
}

/* The share of pixels the front wall of a 3 m CAVE shows lit, seen from the head. */
static double front_wall_lit(const scene *s, const frame_params *p)
{
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    frame_params q = *p;
    gltest_setn(&q, "rsm", 128);
    gltest_setn(&q, "lattice", 16);
    gltest_set(&q, "lpv", "cpu");
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = s, .first = &q};
    renderer *r = renderer_create(&rd, err, sizeof err);
    assert_non_null(r);
    renderer_view v;
    const float bl[3] = {-1.5f, 0, -1.5f}, br[3] = {1.5f, 0, -1.5f}, tl[3] = {-1.5f, 3, -1.5f};
    assert_true(frame_view_screen(bl, br, tl, (const float[3]){0, 1.7f, 0}, scene_far_plane(s), W, H,
                                  &v, NULL) >= 0);
    renderer_frame_pass(r, &q);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(r, &v, 1, &img), 0);
    size_t lit = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        lit += img.direct[3 * i] + img.direct[3 * i + 1] + img.direct[3 * i + 2] > 0;
    renderer_destroy(r);
    glctx_destroy(ctx);
    return (double)lit / ((double)W * H);
}

/* A site exported Z up in centimetres, 100 m from its origin: a 10 x 10 m ground with a
 * 1 m block and a lamp 3 m up. As modelled the CAVE's front wall shows nothing; with the
 * config's scene_transform {"up": "z", "scale": 0.01} (no camera: the ground's middle on
 * the CAVE's floor) it shows the lit ground and block. */
static void test_placed_in_cave(void **state)
{
    (void)state;
    gltf_out g;
    memset(&g, 0, sizeof g);
    const float ground[4][3] = {{10000, 5000, 0}, {11000, 5000, 0}, {11000, 6000, 0}, {10000, 6000, 0}};
    add_quad(&g.mesh[0], ground, (const float[3]){0, 0, 1});
    add_box(&g.mesh[1], (const float[3]){10450, 5200, 0}, (const float[3]){10550, 5300, 100}, 0, 0);
    memcpy(g.mesh[0].color, (const float[3]){0.6f, 0.6f, 0.6f}, sizeof g.mesh[0].color);
    memcpy(g.mesh[1].color, (const float[3]){0.8f, 0.4f, 0.2f}, sizeof g.mesh[1].color);
    g.meshes = 2;
    g.light = "{\"type\":\"point\",\"intensity\":40000}";
    node_matrix((const float[3]){10500, 5500, 300}, (const float[3]){0, 0, -1}, g.light_matrix);
    write_gltf(TMP "site.gltf", &g);
    const char *json =
        "{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"},"
        " \"scene_transform\": {\"up\": \"z\", \"scale\": 0.01}, \"observer\": {\"home\": [0, 1.7, 0]},"
        " \"screens\": [{\"name\": \"front\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [1.5,0,-1.5],"
        " \"top_left\": [-1.5,3,-1.5]}], \"nodes\": [{\"name\": \"a\", \"screens\": [\"front\"], \"resolution\": [4,4]}]}";
    static cluster_config cfg;
    char err[512];
    assert_int_equal(cluster_config_parse(json, strlen(json), "cave.json", &cfg, err, sizeof err), 0);
    double share[2];
    for (int placed = 0; placed < 2; placed++) {
        scene_load_desc d;
        cluster_config_scene_desc(&cfg, &d);
        if (!placed)
            d.transform = NULL;
        scene s;
        assert_int_equal(scene_load_with(TMP "site.gltf", &d, &s, err, sizeof err), 0);
        frame_params p;
        frame_params_default(&p);
        frame_params_lights_from_scene(&p, &s);
        share[placed] = front_wall_lit(&s, &p);
        scene_free(&s);
    }
    printf("site Z up in cm, 100 m away: front wall %.0f%% lit as modelled, %.0f%% placed\n",
           100 * share[0], 100 * share[1]);
    assert_true(share[0] == 0);
    assert_true(share[1] > 0.3);
}

/* A view whose lights are all off receives no light: the eye pass says so (img.lit) and
 * prints one warning, not one per frame; lit again, it says so too. */
static void test_view_without_light(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, 64, 48);
    /* The default room's emissive panel is out of this view's sight only if we look away:
     * switch the panel off too. */
    for (size_t m = 0; m < t.scene.material_count; m++)
        memset(t.scene.materials[m].emissive, 0, sizeof t.scene.materials[m].emissive);
    renderer_destroy(t.r);
    char err[256];
    gltest_setn(&t.params, "lattice", 16);
    renderer_desc rd = {.gl = glctx_gl(t.ctx), .scene = &t.scene, .first = &t.params};
    assert_non_null(t.r = renderer_create(&rd, err, sizeof err));
    renderer_image img;
    for (int f = 0; f < 3; f++) {
        t.params.lights[0].enabled = f != 1;
        renderer_frame_pass(t.r, &t.params);
        assert_int_equal(renderer_eye_pass(t.r, &v, 0, &img), 0);
        assert_int_equal(img.lit, f != 1);
    }
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_light_room),
        cmocka_unit_test(test_orthographic_camera),
        cmocka_unit_test(test_directional_courtyard),
        cmocka_unit_test(test_closed_room_without_lights),
        cmocka_unit_test(test_flat_model),
        cmocka_unit_test(test_textured_box),
        cmocka_unit_test(test_placed_in_cave),
        cmocka_unit_test(test_view_without_light),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
