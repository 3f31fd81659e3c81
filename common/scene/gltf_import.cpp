// gltf_import: glTF 2.0 (.gltf, .glb) from any exporter into the C scene model, through
// tinygltf, and Debian's libdraco for KHR_draco_mesh_compression. The one C++ file of the
// project: everything C++ stays in here behind gltf_import().
//
// Reads meshes of triangles, triangle strips and fans (points and lines carry no surface and
// are skipped), float or quantized attributes (KHR_mesh_quantization) or Draco-compressed
// ones, node transforms, the base colour factor and texture (its TEXCOORD set and
// KHR_texture_transform; KHR_materials_pbrSpecularGlossiness's diffuse colour when a file
// has only that), the emissive factor (times KHR_materials_emissive_strength),
// KHR_lights_punctual lights (`range` is a hint the spec lets renderers ignore, and we do)
// and cameras with their nodes' transforms. extensions[] lists what it honours, what it
// draws differently and what it cannot. Every node whose subtree holds a mesh becomes a
// scene object (scene.h: movable, by the node's name), and the animations' translation,
// rotation and scale channels of those nodes become the scene's animation channels
// (CUBICSPLINE keys by their values, linearly; morph weights are not drawn).
//
// A scene file is untrusted input that every node loads. Before tinygltf sees it: glTF 1.0
// is named as such, and every field the import follows must have its JSON type (rules[]);
// before anything is read, every index, offset, stride, count and type is checked against
// what it refers to (validator). The first violation is refused in one line naming its JSON
// path. Buffers and images come only from the scene file's folder or below (or data: URIs)
// unless the caller allows otherwise, and only from regular files of bounded size. Images
// are decoded here, after the checks, never by tinygltf. What it draws differently from the
// file (materials, vertex colours, ignored extensions) goes into scene.warning, one line.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#include <draco/compression/decode.h>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

extern "C" {
#include "base/json_depth.h"
#include "base/mat4.h"
#include "scene/scene.h"
}

namespace {

using jvalue = nlohmann::json;

// Resource limits: a file may describe more than a node can hold; these turn that into a
// refusal instead of an allocation failure. 2^24 triangles is 1.6 GB of scene arrays.
constexpr size_t max_file_bytes = (size_t)1 << 30;
constexpr size_t max_triangles = (size_t)1 << 24;
constexpr int max_image_side = 16384;
constexpr long long max_image_pixels = 1LL << 26;
constexpr int max_node_depth = 64;

struct refusal : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] void refuse(const std::string &what)
{
    throw refusal(what);
}

std::string item(const std::string &array, size_t i)
{
    return array + "[" + std::to_string(i) + "]";
}

// Index v names one of n things called `what`; -1 only where the field is optional.
void check_index(long long v, size_t n, const std::string &field, const char *what, bool optional)
{
    if (optional && v == -1)
        return;
    if (v < 0 || (unsigned long long)v >= n)
        refuse(field + " " + std::to_string(v) + " out of range (" + std::to_string(n) + " " +
               what + ")");
}

// ---- files: regular files of bounded size, inside the scene's folder unless allowed ----

struct file_policy {
    std::string folder;  // the scene file's folder as tinygltf joins uris to it
    std::string root;    // its real path with a trailing '/'
    bool allow_outside;
    std::string refused; // the first uri refused for lying outside root
};

// The real path of p: a regular file inside the policy's folder (or anywhere, if allowed).
bool resolve(const std::string &p, file_policy *fp, std::string *real)
{
    char buf[PATH_MAX];
    struct stat st;
    if (!realpath(p.c_str(), buf) || stat(buf, &st) != 0 || !S_ISREG(st.st_mode))
        return false;
    if (!fp->allow_outside && std::strncmp(buf, fp->root.c_str(), fp->root.size()) != 0) {
        if (fp->refused.empty()) // name the uri as the file wrote it, never what it found
            fp->refused = p.compare(0, fp->folder.size() + 1, fp->folder + "/") == 0
                              ? p.substr(fp->folder.size() + 1)
                              : p;
        return false;
    }
    *real = buf;
    return true;
}

bool fs_exists(const std::string &path, void *user)
{
    std::string real;
    return resolve(path, static_cast<file_policy *>(user), &real);
}

std::string fs_expand(const std::string &path, void *)
{
    return path;
}

// A whole regular file of at most max_file_bytes; O_NONBLOCK so a FIFO cannot hang us.
bool read_regular(const std::string &path, std::vector<unsigned char> *out, std::string *why)
{
    int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
        (unsigned long long)st.st_size > max_file_bytes) {
        *why = fd < 0 ? std::strerror(errno) : "not a regular file of at most 1 GiB";
        if (fd >= 0)
            close(fd);
        return false;
    }
    out->resize((size_t)st.st_size);
    size_t got = 0;
    while (got < out->size()) {
        ssize_t r = read(fd, out->data() + got, out->size() - got);
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    close(fd);
    out->resize(got);
    return true;
}

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    std::string real, why;
    if (!resolve(path, static_cast<file_policy *>(user), &real)) {
        if (err)
            *err += "not a regular file in the scene's folder\n";
        return false;
    }
    if (!read_regular(real, out, &why)) {
        if (err)
            *err += why + "\n";
        return false;
    }
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err)
        *err += "writing is not supported\n";
    return false;
}

// tinygltf hands over an image's encoded bytes when they come from a uri; images in a
// bufferView are left for the importer, after their view has been checked.
bool keep_encoded(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                  const unsigned char *bytes, int size, void *)
{
    if (image->bufferView < 0 && bytes && size > 0)
        image->image.assign(bytes, bytes + size);
    return true;
}

// ---- the container: GLB or JSON text, glTF 1.0 named, the JSON parsed once for the checks ----

uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

bool is_glb(const std::vector<unsigned char> &b)
{
    return b.size() >= 4 && std::memcmp(b.data(), "glTF", 4) == 0;
}

// The JSON text of a file: all of it, or a GLB's first chunk.
std::string json_text(const std::vector<unsigned char> &b)
{
    if (!is_glb(b))
        return std::string(b.begin(), b.end());
    if (b.size() < 12)
        refuse("binary glTF: shorter than its 12-byte header");
    uint32_t version = le32(b.data() + 4);
    if (version == 1)
        refuse("binary glTF 1.0 (KHR_binary_glTF) is not supported: convert the file to glTF 2.0");
    if (version != 2)
        refuse("binary glTF version " + std::to_string(version) + " is not supported (2)");
    if (b.size() < 20 || le32(b.data() + 16) != 0x4E4F534Au)
        refuse("binary glTF: the first chunk is not JSON");
    uint32_t length = le32(b.data() + 12);
    if (length > b.size() - 20)
        refuse("binary glTF: the JSON chunk's length " + std::to_string(length) +
               " runs past the end of the file");
    return std::string(b.begin() + 20, b.begin() + 20 + length);
}

std::string type_of(const jvalue &v)
{
    if (v.is_number_integer())
        return std::to_string(v.get<long long>());
    if (v.is_number())
        return std::to_string(v.get<double>());
    if (v.is_string())
        return "a string \"" + v.get<std::string>().substr(0, 40) + "\"";
    if (v.is_boolean())
        return v.get<bool>() ? "true" : "false";
    if (v.is_array())
        return "an array of " + std::to_string(v.size());
    return std::string(v.is_object() ? "an object" : "null");
}

jvalue parse_json(const std::string &text)
{
    char deep[120];
    if (json_depth_check(text.data(), text.size(), deep, sizeof deep) != 0)
        refuse(deep);
    try {
        return jvalue::parse(text);
    } catch (const jvalue::parse_error &e) {
        size_t line = 1;
        for (size_t i = 0; i < e.byte && i < text.size(); i++)
            line += text[i] == '\n';
        refuse("not valid JSON near line " + std::to_string(line) + " (byte " +
               std::to_string(e.byte) + "): fix the syntax");
    }
}

// glTF 1.0 says "1.x" in asset.version, or (where asset is missing, as 1.0 allows) keeps its
// collections in dictionaries where glTF 2.0 has arrays.
void check_version(const jvalue &root)
{
    if (!root.is_object())
        refuse("(top level): must be a JSON object, not " + type_of(root));
    auto asset = root.find("asset");
    if (asset != root.end()) {
        auto v = asset->is_object() ? asset->find("version") : asset->end();
        // 1.0 exporters wrote the version as a number; a glTF 2.0 file never does.
        if (v != asset->end() && v->is_number() && v->get<double>() < 2.0)
            refuse("glTF 1.0 is not supported (asset.version is the number " + v->dump() +
                   "): convert the file to glTF 2.0");
        if (v == asset->end() || !v->is_string())
            return; // rules[] names what is wrong with it
        std::string s = v->get<std::string>().substr(0, 20);
        if (s.rfind("1.", 0) == 0 || s == "1")
            refuse("glTF " + s + " is not supported (asset.version): convert the file to glTF 2.0");
        if (s.rfind("2.", 0) != 0)
            refuse("asset.version \"" + s + "\" is not supported (glTF 2.x)");
        return;
    }
    for (const char *key : {"meshes", "nodes", "accessors", "bufferViews", "buffers", "materials", "scenes"}) {
        auto it = root.find(key);
        if (it != root.end() && it->is_object())
            refuse(std::string("glTF 1.0 is not supported (\"") + key +
                   "\" is a dictionary, no \"asset\"): convert the file to glTF 2.0");
    }
    auto scene = root.find("scene");
    if (scene != root.end() && scene->is_string())
        refuse("glTF 1.0 is not supported (\"scene\" is a name, no \"asset\"): convert the file to glTF 2.0");
}

// ---- JSON types: every field the import follows, checked where tinygltf would skip it ----

enum class kind { object, objects, index, indices, index_map, whole, number, numbers, string, strings, boolean };

// A path's "x[]" stands for each element of array x. n: the count of a numbers array (0: any).
struct rule {
    const char *path;
    kind k;
    int n;
    bool required; // when its parent is there
};

#define PBR "materials[].pbrMetallicRoughness"
#define SPEC_GLOSS "materials[].extensions.KHR_materials_pbrSpecularGlossiness"
#define TEX_TRANSFORM PBR ".baseColorTexture.extensions.KHR_texture_transform"
#define DRACO "meshes[].primitives[].extensions.KHR_draco_mesh_compression"
#define LIGHTS "extensions.KHR_lights_punctual.lights"
const rule rules[] = {
    {"asset", kind::object, 0, true}, {"asset.version", kind::string, 0, true},
    {"extensionsUsed", kind::strings, 0, false}, {"extensionsRequired", kind::strings, 0, false},
    {"scene", kind::index, 0, false},
    {"scenes", kind::objects, 0, false}, {"scenes[].nodes", kind::indices, 0, false},
    {"nodes", kind::objects, 0, false}, {"nodes[].children", kind::indices, 0, false},
    {"nodes[].mesh", kind::index, 0, false}, {"nodes[].camera", kind::index, 0, false},
    {"nodes[].matrix", kind::numbers, 16, false}, {"nodes[].translation", kind::numbers, 3, false},
    {"nodes[].rotation", kind::numbers, 4, false}, {"nodes[].scale", kind::numbers, 3, false},
    {"nodes[].name", kind::string, 0, false}, {"nodes[].extensions", kind::object, 0, false},
    {"nodes[].extensions.KHR_lights_punctual", kind::object, 0, false},
    {"nodes[].extensions.KHR_lights_punctual.light", kind::index, 0, true},
    {"meshes", kind::objects, 0, false}, {"meshes[].primitives", kind::objects, 0, true},
    {"meshes[].primitives[].attributes", kind::index_map, 0, true},
    {"meshes[].primitives[].indices", kind::index, 0, false},
    {"meshes[].primitives[].material", kind::index, 0, false},
    {"meshes[].primitives[].mode", kind::index, 0, false},
    {"meshes[].primitives[].extensions", kind::object, 0, false},
    {DRACO, kind::object, 0, false}, {DRACO ".bufferView", kind::index, 0, true},
    {DRACO ".attributes", kind::index_map, 0, true},
    {"accessors", kind::objects, 0, false}, {"accessors[].bufferView", kind::index, 0, false},
    {"accessors[].byteOffset", kind::whole, 0, false}, {"accessors[].componentType", kind::whole, 0, true},
    {"accessors[].count", kind::whole, 0, true}, {"accessors[].type", kind::string, 0, true},
    {"accessors[].normalized", kind::boolean, 0, false}, {"accessors[].sparse", kind::object, 0, false},
    {"bufferViews", kind::objects, 0, false}, {"bufferViews[].buffer", kind::index, 0, true},
    {"bufferViews[].byteOffset", kind::whole, 0, false}, {"bufferViews[].byteLength", kind::whole, 0, true},
    {"bufferViews[].byteStride", kind::whole, 0, false},
    {"buffers", kind::objects, 0, false}, {"buffers[].uri", kind::string, 0, false},
    {"buffers[].byteLength", kind::whole, 0, true},
    {"materials", kind::objects, 0, false}, {PBR, kind::object, 0, false},
    {PBR ".baseColorFactor", kind::numbers, 4, false}, {PBR ".baseColorTexture", kind::object, 0, false},
    {PBR ".baseColorTexture.index", kind::index, 0, true}, {PBR ".baseColorTexture.texCoord", kind::index, 0, false},
    {PBR ".metallicFactor", kind::number, 0, false}, {PBR ".roughnessFactor", kind::number, 0, false},
    {TEX_TRANSFORM, kind::object, 0, false}, {TEX_TRANSFORM ".offset", kind::numbers, 2, false},
    {TEX_TRANSFORM ".rotation", kind::number, 0, false}, {TEX_TRANSFORM ".scale", kind::numbers, 2, false},
    {TEX_TRANSFORM ".texCoord", kind::index, 0, false},
    {"materials[].emissiveFactor", kind::numbers, 3, false}, {"materials[].alphaMode", kind::string, 0, false},
    {"materials[].extensions", kind::object, 0, false},
    {"materials[].extensions.KHR_materials_emissive_strength.emissiveStrength", kind::number, 0, false},
    {SPEC_GLOSS, kind::object, 0, false}, {SPEC_GLOSS ".diffuseFactor", kind::numbers, 4, false},
    {SPEC_GLOSS ".diffuseTexture", kind::object, 0, false}, {SPEC_GLOSS ".diffuseTexture.index", kind::index, 0, true},
    {SPEC_GLOSS ".diffuseTexture.texCoord", kind::index, 0, false},
    {"textures", kind::objects, 0, false}, {"textures[].source", kind::index, 0, false},
    {"images", kind::objects, 0, false}, {"images[].uri", kind::string, 0, false},
    {"images[].bufferView", kind::index, 0, false},
    {"cameras", kind::objects, 0, false}, {"cameras[].type", kind::string, 0, true},
    {"cameras[].perspective", kind::object, 0, false}, {"cameras[].perspective.yfov", kind::number, 0, true},
    {"cameras[].perspective.znear", kind::number, 0, true}, {"cameras[].perspective.zfar", kind::number, 0, false},
    {"cameras[].perspective.aspectRatio", kind::number, 0, false},
    {"cameras[].orthographic", kind::object, 0, false}, {"cameras[].orthographic.xmag", kind::number, 0, true},
    {"cameras[].orthographic.ymag", kind::number, 0, true}, {"cameras[].orthographic.znear", kind::number, 0, true},
    {"cameras[].orthographic.zfar", kind::number, 0, true},
    {"animations", kind::objects, 0, false}, {"animations[].channels", kind::objects, 0, true},
    {"animations[].channels[].sampler", kind::index, 0, true},
    {"animations[].channels[].target", kind::object, 0, true},
    {"animations[].channels[].target.node", kind::index, 0, false},
    {"animations[].channels[].target.path", kind::string, 0, true},
    {"animations[].samplers", kind::objects, 0, true}, {"animations[].samplers[].input", kind::index, 0, true},
    {"animations[].samplers[].output", kind::index, 0, true},
    {"animations[].samplers[].interpolation", kind::string, 0, false},
    {"extensions", kind::object, 0, false}, {"extensions.KHR_lights_punctual", kind::object, 0, false},
    {LIGHTS, kind::objects, 0, false}, {LIGHTS "[].type", kind::string, 0, true},
    {LIGHTS "[].color", kind::numbers, 3, false}, {LIGHTS "[].intensity", kind::number, 0, false},
    {LIGHTS "[].spot", kind::object, 0, false}, {LIGHTS "[].spot.innerConeAngle", kind::number, 0, false},
    {LIGHTS "[].spot.outerConeAngle", kind::number, 0, false},
};
#undef PBR
#undef SPEC_GLOSS
#undef TEX_TRANSFORM
#undef DRACO
#undef LIGHTS

bool is_index(const jvalue &v)
{
    return v.is_number_integer() && v.get<long long>() >= 0 && v.get<long long>() <= INT_MAX;
}

// Whether v is of kind r.k, and what that kind is called.
bool fits(const jvalue &v, const rule &r, std::string *expected)
{
    const auto all = [&v](bool (*ok)(const jvalue &)) {
        for (const jvalue &e : v)
            if (!ok(e))
                return false;
        return true;
    };
    switch (r.k) {
    case kind::object: *expected = "an object"; return v.is_object();
    case kind::objects: *expected = "an array of objects";
        return v.is_array() && all([](const jvalue &e) { return e.is_object(); });
    case kind::index: *expected = "an index (a whole number from 0)"; return is_index(v);
    case kind::indices: *expected = "an array of indices (whole numbers from 0)"; return v.is_array() && all(is_index);
    case kind::index_map: *expected = "an object of indices (whole numbers from 0)"; return v.is_object() && all(is_index);
    case kind::whole: *expected = "a whole number from 0";
        return v.is_number_integer() && v.get<long long>() >= 0;
    case kind::number: *expected = "a number"; return v.is_number();
    case kind::numbers:
        *expected = r.n ? "an array of " + std::to_string(r.n) + " numbers" : "an array of numbers";
        return v.is_array() && (r.n == 0 || v.size() == (size_t)r.n) &&
               all([](const jvalue &e) { return e.is_number(); });
    case kind::string: *expected = "a string"; return v.is_string();
    case kind::strings: *expected = "an array of strings";
        return v.is_array() && all([](const jvalue &e) { return e.is_string(); });
    case kind::boolean: *expected = "true or false"; return v.is_boolean();
    }
    return false;
}

// Checks every value at r.path below node (segments from the path's step-th '.').
void check_rule(const jvalue &node, const rule &r, const char *rest, const std::string &at)
{
    const char *dot = std::strchr(rest, '.');
    std::string seg = dot ? std::string(rest, (size_t)(dot - rest)) : std::string(rest);
    bool each = seg.size() > 2 && seg.compare(seg.size() - 2, 2, "[]") == 0;
    std::string key = each ? seg.substr(0, seg.size() - 2) : seg;
    if (!node.is_object())
        return; // its own rule names the parent's type
    auto it = node.find(key);
    std::string here = at.empty() ? key : at + "." + key;
    std::string expected;
    if (it == node.end()) {
        if (!dot && r.required) {
            fits(jvalue(), r, &expected);
            refuse(here + ": missing (" + expected + " is required)");
        }
        return;
    }
    if (!dot) {
        if (!fits(*it, r, &expected))
            refuse(here + ": must be " + expected + ", not " + type_of(*it));
        return;
    }
    if (!each)
        return check_rule(*it, r, dot + 1, here);
    if (it->is_array())
        for (size_t i = 0; i < it->size(); i++)
            check_rule((*it)[i], r, dot + 1, item(here, i));
}

void check_types(const jvalue &root)
{
    for (const rule &r : rules)
        check_rule(root, r, r.path, "");
}

// ---- extensions: what the import honours, what it draws differently, what it cannot ----

enum class support { honoured, approximated };

struct extension_info {
    const char *name;
    support level;
    const char *drawn; // approximated: how it is drawn instead
};

// Anything not listed is refused when the file requires it and ignored (with a note) when
// it only uses it: the file then carries its own fallback (plain buffers, PNG/JPEG images).
const extension_info extensions[] = {
    {"KHR_lights_punctual", support::honoured, ""},
    {"KHR_materials_emissive_strength", support::honoured, ""},
    {"KHR_texture_transform", support::honoured, ""},
    {"KHR_mesh_quantization", support::honoured, ""},
    {"KHR_draco_mesh_compression", support::honoured, ""},
    {"KHR_materials_variants", support::honoured, ""}, // the default materials, as without a choice
    {"KHR_xmp_json_ld", support::honoured, ""},         // metadata
    {"KHR_materials_pbrSpecularGlossiness", support::approximated, "diffuse colour only"},
    {"KHR_materials_clearcoat", support::approximated, "no clear-coat layer"},
    {"KHR_materials_transmission", support::approximated, "opaque"},
    {"KHR_materials_volume", support::approximated, "opaque"},
    {"KHR_materials_diffuse_transmission", support::approximated, "opaque"},
    {"KHR_materials_sheen", support::approximated, "no sheen"},
    {"KHR_materials_specular", support::approximated, "default specular"},
    {"KHR_materials_ior", support::approximated, "default index of refraction"},
    {"KHR_materials_iridescence", support::approximated, "no iridescence"},
    {"KHR_materials_anisotropy", support::approximated, "isotropic"},
    {"KHR_materials_dispersion", support::approximated, "no dispersion"},
    {"KHR_materials_unlit", support::approximated, "lit"},
};

const extension_info *find_extension(const std::string &name)
{
    for (const extension_info &e : extensions)
        if (name == e.name)
            return &e;
    return nullptr;
}

std::string honoured_list()
{
    std::string s;
    for (const extension_info &e : extensions)
        if (e.level == support::honoured)
            s += std::string(s.empty() ? "" : ", ") + e.name;
    return s;
}

// Refuses a required extension the import cannot honour; notes the used ones it ignores.
void check_extensions(const jvalue &root, std::vector<std::string> *notes)
{
    auto required = root.find("extensionsRequired");
    for (size_t i = 0; required != root.end() && i < required->size(); i++) {
        std::string name = (*required)[i].get<std::string>().substr(0, 60);
        if (!find_extension(name))
            refuse(item("extensionsRequired", i) + ": " + name + " cannot be honoured (this importer reads " +
                   honoured_list() + ", and draws material extensions approximately)");
    }
    std::string ignored;
    auto used = root.find("extensionsUsed");
    for (size_t i = 0; used != root.end() && i < used->size(); i++) {
        std::string name = (*used)[i].get<std::string>().substr(0, 60);
        if (!find_extension(name))
            ignored += (ignored.empty() ? "" : ", ") + name;
    }
    if (!ignored.empty())
        notes->push_back("extensions ignored (their fallbacks used): " + ignored);
}

// ---- validation: everything the importer will follow, checked once, before any read ----

const char *type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

const char *component_name(int c)
{
    switch (c) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

// Triangle modes; POINTS, LINES, LINE_LOOP and LINE_STRIP (0..3) carry no surface.
bool has_triangles(const tinygltf::Primitive &prim)
{
    return prim.mode == -1 || (prim.mode >= TINYGLTF_MODE_TRIANGLES && prim.mode <= TINYGLTF_MODE_TRIANGLE_FAN);
}

const tinygltf::Value *draco_of(const tinygltf::Primitive &prim)
{
    auto ext = prim.extensions.find("KHR_draco_mesh_compression");
    return ext == prim.extensions.end() ? nullptr : &ext->second;
}

// The component types an attribute may have: FLOAT, and KHR_mesh_quantization's 8- and
// 16-bit integers (normalized or not; NORMAL only normalized signed ones).
bool component_ok(const tinygltf::Accessor &a, bool normal)
{
    switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return true;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_SHORT: return !normal || a.normalized;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return !normal;
    default: return false;
    }
}

bool starts_with(const std::string &s, const char *prefix)
{
    return s.rfind(prefix, 0) == 0;
}

struct validator {
    const tinygltf::Model &model;

    void buffer_views()
    {
        for (size_t i = 0; i < model.bufferViews.size(); i++) {
            const tinygltf::BufferView &bv = model.bufferViews[i];
            std::string at = item("bufferViews", i);
            check_index(bv.buffer, model.buffers.size(), at + ".buffer", "buffers", false);
            size_t size = model.buffers[bv.buffer].data.size();
            if (bv.byteLength > size || bv.byteOffset > size - bv.byteLength)
                refuse(at + ": bytes " + std::to_string(bv.byteOffset) + " + " +
                       std::to_string(bv.byteLength) + " outside buffers[" +
                       std::to_string(bv.buffer) + "] (" + std::to_string(size) + " bytes)");
            if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4))
                refuse(at + ".byteStride " + std::to_string(bv.byteStride) +
                       " invalid (4 to 252, a multiple of 4)");
        }
    }

    // An accessor without a bufferView has no data: allowed where Draco supplies it.
    void accessors()
    {
        for (size_t i = 0; i < model.accessors.size(); i++) {
            const tinygltf::Accessor &a = model.accessors[i];
            std::string at = item("accessors", i);
            if (a.sparse.isSparse)
                refuse(at + ".sparse: sparse accessors are not supported");
            int size = tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
            int comps = tinygltf::GetNumComponentsInType((uint32_t)a.type);
            if (size <= 0)
                refuse(at + ".componentType " + std::to_string(a.componentType) + " invalid");
            if (comps <= 0)
                refuse(at + ".type invalid");
            if (a.count < 1)
                refuse(at + ".count 0 invalid (at least 1)");
            if (a.bufferView < 0)
                continue;
            check_index(a.bufferView, model.bufferViews.size(), at + ".bufferView", "bufferViews",
                        false);
            const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
            size_t elem = (size_t)size * (size_t)comps;
            size_t stride = bv.byteStride ? bv.byteStride : elem;
            if (stride < elem)
                refuse(at + ": element of " + std::to_string(elem) + " bytes wider than bufferViews[" +
                       std::to_string(a.bufferView) + "].byteStride " + std::to_string(stride));
            // byteOffset + (count - 1) * stride + elem <= byteLength, without overflow.
            if (a.byteOffset > bv.byteLength || elem > bv.byteLength - a.byteOffset ||
                a.count - 1 > (bv.byteLength - a.byteOffset - elem) / stride)
                refuse(at + ": byteOffset " + std::to_string(a.byteOffset) + " + count " +
                       std::to_string(a.count) + " x stride " + std::to_string(stride) +
                       " outside bufferViews[" + std::to_string(a.bufferView) + "] (" +
                       std::to_string(bv.byteLength) + " bytes)");
        }
    }

    // An accessor the importer reads: its data (unless Draco's) and its type.
    const tinygltf::Accessor &used(int accessor, const std::string &at, bool draco)
    {
        check_index(accessor, model.accessors.size(), at, "accessors", false);
        const tinygltf::Accessor &a = model.accessors[accessor];
        if (!draco && a.bufferView < 0)
            refuse(at + ": accessors[" + std::to_string(accessor) +
                   "].bufferView missing (accessors without data are not supported)");
        return a;
    }

    void attribute(int accessor, const std::string &at, int type, bool normal, bool draco)
    {
        const tinygltf::Accessor &a = used(accessor, at, draco);
        if (a.type != type || !component_ok(a, normal))
            refuse(at + ": accessors[" + std::to_string(accessor) + "] is " + type_name(a.type) +
                   " " + component_name(a.componentType) + ", expected " + type_name(type) +
                   (normal ? " FLOAT (or normalized BYTE/SHORT, KHR_mesh_quantization)"
                           : " FLOAT (or 8/16-bit integers, KHR_mesh_quantization)"));
    }

    void draco(const tinygltf::Primitive &prim, const tinygltf::Value &ext, const std::string &at)
    {
        std::string f = at + ".extensions.KHR_draco_mesh_compression";
        check_index(ext.Get("bufferView").GetNumberAsInt(), model.bufferViews.size(),
                    f + ".bufferView", "bufferViews", false);
        const tinygltf::Value &attrs = ext.Get("attributes");
        if (!attrs.Has("POSITION"))
            refuse(f + ".attributes: no POSITION");
        for (const std::string &name : attrs.Keys())
            if (!prim.attributes.count(name))
                refuse(f + ".attributes." + name.substr(0, 40) + ": not among the primitive's attributes");
    }

    void primitive(const tinygltf::Primitive &prim, const std::string &at)
    {
        for (const auto &kv : prim.attributes)
            check_index(kv.second, model.accessors.size(), at + ".attributes." + kv.first, "accessors", false);
        check_index(prim.material, model.materials.size(), at + ".material", "materials", true);
        if (prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            refuse(at + ".mode " + std::to_string(prim.mode) + " invalid (0 to 6)");
        if (!has_triangles(prim))
            return; // points and lines carry no surfaces: skipped
        const tinygltf::Value *dr = draco_of(prim);
        if (dr)
            draco(prim, *dr, at);
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end())
            refuse(at + ".attributes: no POSITION");
        attribute(pos->second, at + ".attributes.POSITION", TINYGLTF_TYPE_VEC3, false, dr);
        size_t vertices = model.accessors[pos->second].count;
        for (const auto &kv : prim.attributes) {
            bool normal = kv.first == "NORMAL", uv = starts_with(kv.first, "TEXCOORD_");
            if (!normal && !uv)
                continue; // not read (COLOR_0 and the like are noted by the importer)
            std::string field = at + ".attributes." + kv.first;
            attribute(kv.second, field, uv ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3, normal, dr);
            if (!dr && model.accessors[kv.second].count != vertices)
                refuse(field + ": count " + std::to_string(model.accessors[kv.second].count) +
                       " differs from POSITION's " + std::to_string(vertices));
        }
        if (prim.indices < 0)
            return;
        const tinygltf::Accessor &ia = used(prim.indices, at + ".indices", dr);
        if (ia.type != TINYGLTF_TYPE_SCALAR ||
            (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            refuse(at + ".indices: accessors[" + std::to_string(prim.indices) + "] is " +
                   type_name(ia.type) + " " + component_name(ia.componentType) +
                   ", expected SCALAR UNSIGNED_BYTE/SHORT/INT");
    }

    void meshes()
    {
        for (size_t m = 0; m < model.meshes.size(); m++)
            for (size_t p = 0; p < model.meshes[m].primitives.size(); p++)
                primitive(model.meshes[m].primitives[p], item(item("meshes", m) + ".primitives", p));
    }

    void texture_info(int index, const std::string &at)
    {
        check_index(index, model.textures.size(), at + ".index", "textures", true);
    }

    void materials()
    {
        for (size_t i = 0; i < model.images.size(); i++) {
            const tinygltf::Image &img = model.images[i];
            check_index(img.bufferView, model.bufferViews.size(), item("images", i) + ".bufferView",
                        "bufferViews", true);
        }
        for (size_t i = 0; i < model.textures.size(); i++)
            check_index(model.textures[i].source, model.images.size(),
                        item("textures", i) + ".source", "images", true);
        for (size_t i = 0; i < model.materials.size(); i++) {
            const tinygltf::Material &m = model.materials[i];
            std::string at = item("materials", i);
            texture_info(m.pbrMetallicRoughness.baseColorTexture.index,
                         at + ".pbrMetallicRoughness.baseColorTexture");
            auto sg = m.extensions.find("KHR_materials_pbrSpecularGlossiness");
            if (sg != m.extensions.end() && sg->second.Has("diffuseTexture"))
                texture_info(sg->second.Get("diffuseTexture").Get("index").GetNumberAsInt(),
                             at + ".extensions.KHR_materials_pbrSpecularGlossiness.diffuseTexture");
        }
    }

    // Nodes form a forest: each has at most one parent, scenes name roots once each.
    void nodes()
    {
        std::vector<long long> parent(model.nodes.size(), -1);
        for (size_t i = 0; i < model.nodes.size(); i++) {
            const tinygltf::Node &n = model.nodes[i];
            std::string at = item("nodes", i);
            check_index(n.mesh, model.meshes.size(), at + ".mesh", "meshes", true);
            check_index(n.camera, model.cameras.size(), at + ".camera", "cameras", true);
            for (size_t c = 0; c < n.children.size(); c++) {
                std::string field = item(at + ".children", c);
                check_index(n.children[c], model.nodes.size(), field, "nodes", false);
                long long &p = parent[n.children[c]];
                if (p >= 0 || (size_t)n.children[c] == i)
                    refuse(field + ": nodes[" + std::to_string(n.children[c]) + "] already has a parent (" +
                           (p >= 0 ? item("nodes", (size_t)p) : at) + "); nodes must form trees");
                p = (long long)i;
            }
            auto ext = n.extensions.find("KHR_lights_punctual");
            if (ext != n.extensions.end() && ext->second.Has("light")) {
                check_index(ext->second.Get("light").GetNumberAsInt(), model.lights.size(),
                            at + ".extensions.KHR_lights_punctual.light", "lights", false);
            }
        }
        for (size_t i = 0; i < model.nodes.size(); i++) { // a cycle has no root above it
            size_t steps = 0;
            for (long long p = parent[i]; p >= 0; p = parent[p])
                if (++steps > (size_t)max_node_depth)
                    refuse(item("nodes", i) + ": nested deeper than " + std::to_string(max_node_depth) +
                           " levels or in a cycle");
        }
        check_index(model.defaultScene, model.scenes.size(), "scene", "scenes", true);
        for (size_t s = 0; s < model.scenes.size(); s++) {
            std::vector<bool> seen(model.nodes.size(), false);
            for (size_t k = 0; k < model.scenes[s].nodes.size(); k++) {
                std::string field = item(item("scenes", s) + ".nodes", k);
                int n = model.scenes[s].nodes[k];
                check_index(n, model.nodes.size(), field, "nodes", false);
                if (parent[n] >= 0 || seen[n])
                    refuse(field + ": nodes[" + std::to_string(n) + "] is not a root or is listed twice");
                seen[n] = true;
            }
        }
    }

    // A number the importer uses: finite and within [lo, hi] (open ends where asked).
    static void check_number(double v, const std::string &field, double lo, double hi,
                             bool lo_open, bool hi_open, const char *range)
    {
        if (!std::isfinite(v) || v < lo || v > hi || (lo_open && v == lo) || (hi_open && v == hi))
            refuse(field + " " + std::to_string(v) + " invalid (" + range + ")");
    }

    void lights()
    {
        const double half_pi = 1.5707963267948966;
        for (size_t i = 0; i < model.lights.size(); i++) {
            const tinygltf::Light &l = model.lights[i];
            std::string at = item("extensions.KHR_lights_punctual.lights", i);
            if (l.type != "spot" && l.type != "point" && l.type != "directional")
                refuse(at + ".type \"" + l.type.substr(0, 40) +
                       "\" unknown (spot, point or directional)");
            check_number(l.intensity, at + ".intensity", 0, 1e12, false, false, "0 to 1e12");
            for (size_t c = 0; c < l.color.size(); c++)
                check_number(l.color[c], item(at + ".color", c), 0, 1e12, false, false, "0 to 1e12");
            if (l.type != "spot")
                continue;
            check_number(l.spot.outerConeAngle, at + ".spot.outerConeAngle", 0, half_pi, true,
                         false, "0 < outer <= pi/2");
            check_number(l.spot.innerConeAngle, at + ".spot.innerConeAngle", 0,
                         l.spot.outerConeAngle, false, false, "0 <= inner <= outer");
        }
    }

    void cameras()
    {
        const double pi = 3.141592653589793;
        for (size_t i = 0; i < model.cameras.size(); i++) {
            const tinygltf::Camera &c = model.cameras[i];
            std::string at = item("cameras", i);
            if (c.type == "perspective") {
                const tinygltf::PerspectiveCamera &p = c.perspective;
                check_number(p.yfov, at + ".perspective.yfov", 0, pi, true, true, "0 < yfov < pi");
                check_number(p.znear, at + ".perspective.znear", 0, 1e30, true, false, "> 0");
                check_number(p.aspectRatio, at + ".perspective.aspectRatio", 0, 1e6, false, false,
                             "> 0");
                if (p.zfar != 0)
                    check_number(p.zfar, at + ".perspective.zfar", p.znear, 1e30, true, false,
                                 "> znear");
            } else if (c.type == "orthographic") {
                const tinygltf::OrthographicCamera &o = c.orthographic;
                check_number(o.xmag, at + ".orthographic.xmag", 0, 1e30, true, false, "> 0");
                check_number(o.ymag, at + ".orthographic.ymag", 0, 1e30, true, false, "> 0");
                check_number(o.znear, at + ".orthographic.znear", 0, 1e30, false, false, ">= 0");
                check_number(o.zfar, at + ".orthographic.zfar", o.znear, 1e30, true, false,
                             "> znear");
            } else {
                refuse(at + ".type \"" + c.type.substr(0, 40) +
                       "\" unknown (perspective or orthographic)");
            }
        }
    }

    void run()
    {
        buffer_views();
        accessors();
        meshes();
        materials();
        lights();
        cameras();
        nodes();
    }
};


// ---- import: reads only what the checks accepted ----

struct mat4 {
    double m[16]; // column-major
};

mat4 identity()
{
    mat4 r;
    mat4d_identity(r.m);
    return r;
}

mat4 mul(const mat4 &a, const mat4 &b)
{
    mat4 r;
    mat4d_mul(a.m, b.m, r.m);
    return r;
}

mat4 node_local(const tinygltf::Node &n)
{
    if (n.matrix.size() == 16) {
        mat4 r;
        for (int i = 0; i < 16; i++)
            r.m[i] = n.matrix[i];
        return r;
    }
    mat4 t = identity(), rot = identity(), s = identity();
    if (n.translation.size() == 3)
        for (int i = 0; i < 3; i++)
            t.m[12 + i] = n.translation[i];
    if (n.rotation.size() == 4) {
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        rot.m[0] = 1 - 2 * (y * y + z * z); rot.m[1] = 2 * (x * y + z * w); rot.m[2] = 2 * (x * z - y * w);
        rot.m[4] = 2 * (x * y - z * w); rot.m[5] = 1 - 2 * (x * x + z * z); rot.m[6] = 2 * (y * z + x * w);
        rot.m[8] = 2 * (x * z + y * w); rot.m[9] = 2 * (y * z - x * w); rot.m[10] = 1 - 2 * (x * x + y * y);
    }
    if (n.scale.size() == 3)
        for (int i = 0; i < 3; i++)
            s.m[i * 5] = n.scale[i];
    return mul(t, mul(rot, s));
}

void transform_point(const mat4 &m, const float in[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (float)(m.m[r] * in[0] + m.m[4 + r] * in[1] + m.m[8 + r] * in[2] + m.m[12 + r]);
}

// Normals go through the inverse transpose of the upper 3x3 (the cofactor matrix is
// proportional to it, and the scene normalizes afterwards).
void transform_normal(const mat4 &m, const float in[3], float out[3])
{
    const double *a = m.m;
    double c[9] = {
        a[5] * a[10] - a[6] * a[9], a[6] * a[8] - a[4] * a[10], a[4] * a[9] - a[5] * a[8],
        a[9] * a[2] - a[10] * a[1], a[10] * a[0] - a[8] * a[2], a[8] * a[1] - a[9] * a[0],
        a[1] * a[6] - a[2] * a[5], a[2] * a[4] - a[0] * a[6], a[0] * a[5] - a[1] * a[4],
    };
    // c[3*col + row] is the cofactor of element (row, col) of the column-major 3x3.
    for (int r = 0; r < 3; r++)
        out[r] = (float)(c[r] * in[0] + c[3 + r] * in[1] + c[6 + r] * in[2]);
}


// One primitive's vertices and triangles, from accessors or from Draco.
struct mesh_data {
    size_t vertices = 0;
    std::vector<float> pos, nrm, uv; // 3, 3, 2 floats per vertex; nrm, uv empty when absent
    std::vector<uint32_t> corners;   // 3 vertex indices per triangle
};

// How a material maps uvs: its texture's TEXCOORD set, then KHR_texture_transform's
// u' = m0 u + m1 v + m2, v' = m3 u + m4 v + m5 (offset, rotation, scale: T * R * S).
struct uv_map {
    int set = 0;
    double m[6] = {1, 0, 0, 0, 1, 0};
};

float component(const unsigned char *p, int type, bool normalized)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t c;
        std::memcpy(&c, p, 1);
        return normalized ? std::fmax(c / 127.0f, -1.0f) : (float)c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : (float)p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t c;
        std::memcpy(&c, p, 2);
        return normalized ? std::fmax(c / 32767.0f, -1.0f) : (float)c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t c;
        std::memcpy(&c, p, 2);
        return normalized ? c / 65535.0f : (float)c;
    }
    default: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    }
}

// The triangles of an element sequence in a glTF mode (TRIANGLES, TRIANGLE_STRIP with
// alternating winding, TRIANGLE_FAN around the first), without degenerate ones (strips
// join their runs with those).
void triangulate(int mode, const std::vector<uint32_t> &seq, std::vector<uint32_t> *out)
{
    size_t n = seq.size();
    size_t count = mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN
                       ? (n >= 3 ? n - 2 : 0)
                       : n / 3;
    out->reserve(3 * count);
    for (size_t i = 0; i < count; i++) {
        uint32_t a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            a = seq[i];
            b = seq[i + 1 + i % 2];
            c = seq[i + 2 - i % 2];
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            a = seq[i + 1];
            b = seq[i + 2];
            c = seq[0];
        } else {
            a = seq[3 * i];
            b = seq[3 * i + 1];
            c = seq[3 * i + 2];
        }
        if (a != b && b != c && a != c)
            out->insert(out->end(), {a, b, c});
    }
}

struct importer {
    const tinygltf::Model &model;
    scene *out;
    std::vector<std::string> &notes;
    std::vector<int> material_index; // glTF material -> scene material
    std::vector<uv_map> uv_maps;     // glTF material -> its uv mapping
    int default_material = -1;
    bool vertex_colours = false;
    int lights_dropped = 0;
    std::vector<int> node_object;    // glTF node -> its scene object, -1: none of its own
    std::vector<signed char> holds;  // glTF node -> its subtree holds a mesh (-1: not known yet)
    int objects_dropped = 0;
    int channels_ignored = 0;

    const unsigned char *element(int accessor, size_t i) const
    {
        const tinygltf::Accessor &a = model.accessors[accessor];
        const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
        size_t elem = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType) *
                      (size_t)tinygltf::GetNumComponentsInType((uint32_t)a.type);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        return model.buffers[bv.buffer].data.data() + bv.byteOffset + a.byteOffset + i * stride;
    }

    // Every element's comps components as floats (quantized ones as KHR_mesh_quantization says).
    void read_floats(int accessor, int comps, std::vector<float> *v) const
    {
        const tinygltf::Accessor &a = model.accessors[accessor];
        int size = tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
        v->resize(a.count * (size_t)comps);
        for (size_t i = 0; i < a.count; i++) {
            const unsigned char *p = element(accessor, i);
            for (int k = 0; k < comps; k++)
                (*v)[i * (size_t)comps + (size_t)k] = component(p + k * size, a.componentType, a.normalized);
        }
    }

    // The element sequence: the indices (each checked against the vertices) or 0..n-1.
    std::vector<uint32_t> sequence(const tinygltf::Primitive &prim, size_t vertices,
                                   const std::string &at) const
    {
        std::vector<uint32_t> seq;
        if (prim.indices < 0) {
            seq.resize(vertices);
            for (size_t i = 0; i < vertices; i++)
                seq[i] = (uint32_t)i;
            return seq;
        }
        const tinygltf::Accessor &ia = model.accessors[prim.indices];
        seq.resize(ia.count);
        for (size_t i = 0; i < ia.count; i++) {
            const unsigned char *p = element(prim.indices, i);
            uint32_t idx = p[0];
            if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                uint16_t s;
                std::memcpy(&s, p, 2);
                idx = s;
            } else if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
                std::memcpy(&idx, p, 4);
            }
            if (idx >= vertices)
                refuse(at + ".indices: accessors[" + std::to_string(prim.indices) + "][" +
                       std::to_string(i) + "] = " + std::to_string(idx) + " out of range (" +
                       std::to_string(vertices) + " vertices)");
            seq[i] = idx;
        }
        return seq;
    }

    void from_accessors(const tinygltf::Primitive &prim, const std::string &uv_name,
                        const std::string &at, mesh_data *d) const
    {
        int pos = prim.attributes.at("POSITION");
        d->vertices = model.accessors[pos].count;
        if (d->vertices > 3 * max_triangles)
            refuse(at + ".attributes.POSITION: more than " + std::to_string(3 * max_triangles) + " vertices");
        read_floats(pos, 3, &d->pos);
        auto nrm = prim.attributes.find("NORMAL"), tex = prim.attributes.find(uv_name);
        if (nrm != prim.attributes.end())
            read_floats(nrm->second, 3, &d->nrm);
        if (tex != prim.attributes.end())
            read_floats(tex->second, 2, &d->uv);
        triangulate(prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode,
                    sequence(prim, d->vertices, at), &d->corners);
    }

    // A Draco attribute's values for every point, or empty when the file maps none.
    static void draco_attribute(const draco::Mesh &mesh, const tinygltf::Value &ids, const std::string &name,
                                int comps, const std::string &at, std::vector<float> *v)
    {
        if (!ids.Has(name))
            return;
        int id = ids.Get(name).GetNumberAsInt();
        const draco::PointAttribute *a = mesh.GetAttributeByUniqueId((uint32_t)id);
        if (!a || a->num_components() < comps)
            refuse(at + ".attributes." + name + ": no Draco attribute " + std::to_string(id) + " of " +
                   std::to_string(comps) + " components in the compressed data");
        v->resize(mesh.num_points() * (size_t)comps);
        for (uint32_t p = 0; p < mesh.num_points(); p++)
            if (!a->ConvertValue<float>(a->mapped_index(draco::PointIndex(p)), (int8_t)comps,
                                        v->data() + (size_t)p * (size_t)comps))
                refuse(at + ".attributes." + name + ": Draco values not convertible to numbers");
    }

    void from_draco(const tinygltf::Value &ext, const std::string &uv_name, const std::string &at,
                    mesh_data *d) const
    {
        std::string f = at + ".extensions.KHR_draco_mesh_compression";
        const tinygltf::BufferView &bv = model.bufferViews[ext.Get("bufferView").GetNumberAsInt()];
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char *>(model.buffers[bv.buffer].data.data() + bv.byteOffset),
                    bv.byteLength);
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok())
            refuse(f + ": cannot decode (" + decoded.status().error_msg_string().substr(0, 80) + ")");
        std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
        if (mesh->num_faces() > max_triangles || mesh->num_points() > 3 * max_triangles)
            refuse(f + ": more than " + std::to_string(max_triangles) + " triangles");
        d->vertices = mesh->num_points();
        const tinygltf::Value &ids = ext.Get("attributes");
        draco_attribute(*mesh, ids, "POSITION", 3, f, &d->pos);
        draco_attribute(*mesh, ids, "NORMAL", 3, f, &d->nrm);
        draco_attribute(*mesh, ids, uv_name, 2, f, &d->uv);
        std::vector<uint32_t> seq;
        seq.reserve(3 * (size_t)mesh->num_faces());
        for (draco::FaceIndex i(0); i < mesh->num_faces(); ++i)
            for (int k = 0; k < 3; k++) {
                uint32_t v = mesh->face(i)[k].value();
                if (v >= d->vertices)
                    refuse(f + ": a face refers to point " + std::to_string(v) + " of " +
                           std::to_string(d->vertices));
                seq.push_back(v);
            }
        triangulate(TINYGLTF_MODE_TRIANGLES, seq, &d->corners);
    }

    void primitive(const tinygltf::Primitive &prim, const mat4 &world, const std::string &at)
    {
        if (!has_triangles(prim))
            return;
        vertex_colours |= prim.attributes.count("COLOR_0") > 0;
        const uv_map &map = prim.material >= 0 ? uv_maps[prim.material] : uv_map();
        std::string uv_name = "TEXCOORD_" + std::to_string(map.set);
        mesh_data d;
        const tinygltf::Value *dr = draco_of(prim);
        if (dr)
            from_draco(*dr, uv_name, at, &d);
        else
            from_accessors(prim, uv_name, at, &d);
        size_t count = d.corners.size() / 3;
        if (count > max_triangles - out->triangle_count)
            refuse(at + ": more than " + std::to_string(max_triangles) + " triangles in the scene");
        uint32_t material = prim.material >= 0 ? (uint32_t)material_index[prim.material]
                                               : (uint32_t)default_material;
        bool have_n = !d.nrm.empty(), have_uv = !d.uv.empty();
        for (size_t t = 0; t < count; t++) {
            float p[9], n[9], uv[6];
            for (int k = 0; k < 3; k++) {
                size_t v = d.corners[3 * t + (size_t)k];
                transform_point(world, &d.pos[3 * v], p + 3 * k);
                if (have_n)
                    transform_normal(world, &d.nrm[3 * v], n + 3 * k);
                if (have_uv) {
                    double u = d.uv[2 * v], w = d.uv[2 * v + 1];
                    uv[2 * k] = (float)(map.m[0] * u + map.m[1] * w + map.m[2]);
                    uv[2 * k + 1] = (float)(map.m[3] * u + map.m[4] * w + map.m[5]);
                }
            }
            if (scene_add_triangle(out, p, have_n ? n : nullptr, have_uv ? uv : nullptr,
                                   material) < 0)
                refuse("out of memory");
        }
    }
    // The node's -Z axis in the world, unit; false when its transform flattens it.
    static bool axis(const mat4 &world, int column, double sign, float out[3])
    {
        double d[3] = {sign * world.m[4 * column], sign * world.m[4 * column + 1],
                       sign * world.m[4 * column + 2]};
        double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(len > 0) || !std::isfinite(len))
            return false;
        for (int a = 0; a < 3; a++)
            out[a] = (float)(d[a] / len);
        return true;
    }

    void light(int li, const mat4 &world)
    {
        const tinygltf::Light &l = model.lights[li];
        scene_light sl{};
        const float zero[3] = {0, 0, 0};
        transform_point(world, zero, sl.position);
        if (!axis(world, 2, -1.0, sl.direction)) // spot axis and travel: the node's -Z
            sl.direction[1] = -1.0f;
        for (int a = 0; a < 3; a++)
            sl.color[a] = l.color.size() == 3 ? (float)l.color[a] : 1.0f;
        sl.intensity = (float)l.intensity;
        if (l.type == "spot") {
            sl.type = SCENE_LIGHT_SPOT;
            sl.outer_angle = (float)l.spot.outerConeAngle;
            sl.inner_angle = (float)l.spot.innerConeAngle;
        } else {
            sl.type = l.type == "point" ? SCENE_LIGHT_POINT : SCENE_LIGHT_DIRECTIONAL;
        }
        if (scene_add_light(out, &sl) < 0)
            lights_dropped++;
    }

    static void name_copy(char *dst, size_t n, const std::string &src)
    {
        std::snprintf(dst, n, "%s", src.c_str());
    }

    void camera(const tinygltf::Node &n, const mat4 &world, const std::string &at)
    {
        const tinygltf::Camera &c = model.cameras[n.camera];
        scene_camera sc{};
        const float zero[3] = {0, 0, 0};
        transform_point(world, zero, sc.position);
        float forward[3];
        if (!axis(world, 2, -1.0, forward) || !axis(world, 1, 1.0, sc.up) ||
            std::fabs(forward[0] * sc.up[0] + forward[1] * sc.up[1] + forward[2] * sc.up[2]) > 0.999f)
            refuse(at + ": the camera's transform has no view direction or up (zero scale?)");
        for (int a = 0; a < 3; a++)
            sc.target[a] = sc.position[a] + forward[a];
        sc.valid = 1;
        if (c.type == "orthographic") {
            sc.orthographic = 1;
            sc.ymag = (float)c.orthographic.ymag;
            sc.aspect = (float)(c.orthographic.xmag / c.orthographic.ymag);
            sc.znear = (float)c.orthographic.znear;
            sc.zfar = (float)c.orthographic.zfar;
        } else {
            sc.yfov = (float)c.perspective.yfov;
            sc.aspect = (float)c.perspective.aspectRatio;
            sc.znear = (float)c.perspective.znear;
            sc.zfar = (float)c.perspective.zfar;
        }
        name_copy(sc.name, sizeof sc.name, n.name.empty() ? c.name : n.name);
        name_copy(sc.camera_name, sizeof sc.camera_name, c.name);
        if (scene_add_camera(out, &sc) < 0)
            refuse("out of memory");
    }

    bool holds_mesh(int index)
    {
        if (holds[index] < 0) {
            const tinygltf::Node &n = model.nodes[index];
            bool any = n.mesh >= 0;
            for (int child : n.children)
                any = holds_mesh(child) || any;
            holds[index] = any;
        }
        return holds[index] != 0;
    }

    // The node's own object (when its subtree holds a mesh): named as in the file, with its
    // rest transform; past SCENE_MAX_OBJECTS its triangles stay with its parent's object.
    int begin_object(int index, const mat4 &world, int parent_object)
    {
        const tinygltf::Node &n = model.nodes[index];
        if (!holds_mesh(index))
            return parent_object;
        std::string name = n.name.empty() ? "node" + std::to_string(index) : n.name;
        int o = scene_begin_object(out, name.c_str(), parent_object);
        if (o < 0) {
            objects_dropped++;
            scene_end_object(out, parent_object);
            return parent_object;
        }
        scene_object *ob = &out->objects[o];
        for (int k = 0; k < 3 && n.translation.size() == 3; k++)
            ob->rest_translation[k] = (float)n.translation[k];
        for (int k = 0; k < 4 && n.rotation.size() == 4; k++)
            ob->rest_rotation[k] = (float)n.rotation[k];
        for (int k = 0; k < 3 && n.scale.size() == 3; k++)
            ob->rest_scale[k] = (float)n.scale[k];
        for (int k = 0; k < 16; k++)
            ob->rest_world[k] = (float)world.m[k];
        node_object[index] = o;
        return o;
    }

    void node(int index, const mat4 &parent, int parent_object)
    {
        const tinygltf::Node &n = model.nodes[index];
        mat4 world = mul(parent, node_local(n));
        int object = begin_object(index, world, parent_object);
        scene_end_object(out, object); /* this node's triangles are its object's */
        if (n.mesh >= 0) {
            const tinygltf::Mesh &m = model.meshes[n.mesh];
            for (size_t p = 0; p < m.primitives.size(); p++)
                primitive(m.primitives[p], world, item(item("meshes", n.mesh) + ".primitives", p));
        }
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end() && ext->second.Has("light"))
            light(ext->second.Get("light").GetNumberAsInt(), world);
        if (n.camera >= 0)
            camera(n, world, item("nodes", (size_t)index));
        for (int child : n.children)
            node(child, world, object);
    }

    // Decodes one image to RGBA8 (sRGB-encoded, as glTF stores base colour).
    int texture(int image)
    {
        const tinygltf::Image &img = model.images[image];
        std::string at = item("images", (size_t)image);
        const unsigned char *bytes;
        size_t size;
        if (img.bufferView >= 0) {
            const tinygltf::BufferView &bv = model.bufferViews[img.bufferView];
            bytes = model.buffers[bv.buffer].data.data() + bv.byteOffset;
            size = bv.byteLength;
        } else {
            bytes = img.image.data();
            size = img.image.size();
        }
        if (size == 0)
            refuse(at + (img.uri.empty() ? ": no data"
                                         : ".uri \"" + img.uri.substr(0, 80) + "\": file not found or empty"));
        int w, h, c;
        if (size > INT32_MAX || !stbi_info_from_memory(bytes, (int)size, &w, &h, &c))
            refuse(at + ": cannot decode (" + (stbi_failure_reason() ? stbi_failure_reason() : "unknown format") + ")");
        if (w > max_image_side || h > max_image_side || (long long)w * h > max_image_pixels)
            refuse(at + ": " + std::to_string(w) + "x" + std::to_string(h) + " is larger than " +
                   std::to_string(max_image_side) + " a side or 2^26 pixels");
        uint8_t *rgba = stbi_load_from_memory(bytes, (int)size, &w, &h, &c, 4);
        if (!rgba)
            refuse(at + ": cannot decode (" + (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
        // The scene owns malloc'ed pixels; stb_image's allocator is malloc.
        int t = scene_add_texture(out, w, h, rgba);
        if (t < 0) {
            stbi_image_free(rgba);
            refuse("out of memory");
        }
        return t;
    }


    // A texture reference's uv mapping: its TEXCOORD set and KHR_texture_transform.
    static uv_map mapping(int texcoord, const tinygltf::ExtensionMap &ext)
    {
        uv_map map;
        map.set = texcoord;
        auto tt = ext.find("KHR_texture_transform");
        if (tt == ext.end())
            return map;
        const tinygltf::Value &v = tt->second;
        double off[2] = {0, 0}, scale[2] = {1, 1}, rot = 0;
        for (int k = 0; k < 2; k++) {
            if (v.Has("offset"))
                off[k] = v.Get("offset").Get(k).GetNumberAsDouble();
            if (v.Has("scale"))
                scale[k] = v.Get("scale").Get(k).GetNumberAsDouble();
        }
        if (v.Has("rotation"))
            rot = v.Get("rotation").GetNumberAsDouble();
        if (v.Has("texCoord"))
            map.set = v.Get("texCoord").GetNumberAsInt();
        double c = std::cos(rot), s = std::sin(rot);
        const double m[6] = {c * scale[0], s * scale[1], off[0], -s * scale[0], c * scale[1], off[1]};
        std::memcpy(map.m, m, sizeof m);
        return map;
    }

    // What of material i the renderer draws differently from its definition.
    static std::string differences(const tinygltf::Material &m, bool spec_gloss)
    {
        std::string why;
        for (const auto &kv : m.extensions) {
            const extension_info *e = find_extension(kv.first);
            if (e && e->level == support::approximated)
                why += (why.empty() ? "" : ", ") + kv.first + ": " + e->drawn;
        }
        if (m.alphaMode == "BLEND" || m.alphaMode == "MASK")
            why += std::string(why.empty() ? "" : ", ") + "alphaMode " + m.alphaMode + ": opaque";
        if (!spec_gloss && m.pbrMetallicRoughness.metallicFactor >= 0.5)
            why += std::string(why.empty() ? "" : ", ") + "metallic: as a non-metal";
        return why;
    }

    int texture_of(int t, std::vector<int> &decoded)
    {
        int src = model.textures[t].source;
        if (src < 0) {
            notes.push_back(item("textures", (size_t)t) +
                            " has no PNG or JPEG source: drawn untextured");
            return -1;
        }
        if (decoded[src] < 0)
            decoded[src] = texture(src);
        return decoded[src];
    }

    void material(const tinygltf::Material &m, std::vector<int> &decoded, std::string *differ)
    {
        scene_material sm{};
        const auto &pbr = m.pbrMetallicRoughness;
        std::vector<double> factor = pbr.baseColorFactor;
        int tex = pbr.baseColorTexture.index;
        uv_map map = mapping(pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions);
        // Specular-glossiness: its diffuse colour is the base colour a diffuse renderer wants.
        auto sg = m.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (sg != m.extensions.end()) {
            if (sg->second.Has("diffuseFactor"))
                for (int k = 0; k < 4; k++)
                    factor[k] = sg->second.Get("diffuseFactor").Get(k).GetNumberAsDouble();
            if (sg->second.Has("diffuseTexture")) {
                const tinygltf::Value &dt = sg->second.Get("diffuseTexture");
                tex = dt.Get("index").GetNumberAsInt();
                map = uv_map();
                map.set = dt.Has("texCoord") ? dt.Get("texCoord").GetNumberAsInt() : 0;
            }
        }
        for (int k = 0; k < 4; k++)
            sm.base_color[k] = factor.size() == 4 ? (float)factor[k] : 1.0f;
        sm.base_color_texture = tex >= 0 ? texture_of(tex, decoded) : -1;
        double strength = 1.0;
        auto es = m.extensions.find("KHR_materials_emissive_strength");
        if (es != m.extensions.end() && es->second.Has("emissiveStrength"))
            strength = es->second.Get("emissiveStrength").GetNumberAsDouble();
        for (int k = 0; k < 3; k++)
            sm.emissive[k] = m.emissiveFactor.size() == 3 ? (float)(m.emissiveFactor[k] * strength) : 0.0f;
        sm.roughness = (float)pbr.roughnessFactor;
        int index = scene_add_material(out, &sm);
        if (index < 0)
            refuse("out of memory");
        material_index.push_back(index);
        uv_maps.push_back(map);
        *differ = differences(m, sg != m.extensions.end());
    }

    void materials()
    {
        std::vector<int> decoded(model.images.size(), -1);
        std::string list;
        size_t differ_count = 0;
        for (size_t i = 0; i < model.materials.size(); i++) {
            std::string differ;
            material(model.materials[i], decoded, &differ);
            if (differ.empty())
                continue;
            if (++differ_count <= 3) {
                const std::string &name = model.materials[i].name;
                list += (list.empty() ? "" : "; ") + item("materials", i) +
                        (name.empty() ? "" : " \"" + name.substr(0, 40) + "\"") + " (" + differ + ")";
            }
        }
        if (differ_count)
            notes.push_back(std::to_string(differ_count) + " of " + std::to_string(model.materials.size()) +
                            " materials drawn differently from the file: " + list +
                            (differ_count > 3 ? "; ..." : ""));
        scene_material fallback = {{0.8f, 0.8f, 0.8f, 1.0f}, -1, {0, 0, 0}, 0.5f};
        default_material = scene_add_material(out, &fallback);
        if (default_material < 0)
            refuse("out of memory");
    }

    // A sampler's keyframe times: float, finite, increasing.
    std::vector<float> key_times(int accessor, const std::string &at)
    {
        const tinygltf::Accessor &a = used(accessor, at, false);
        if (a.type != TINYGLTF_TYPE_SCALAR || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            refuse(at + ": accessors[" + std::to_string(accessor) + "] must be SCALAR floats (keyframe times)");
        std::vector<float> t;
        read_floats(accessor, 1, &t);
        for (size_t i = 0; i < t.size(); i++)
            if (!std::isfinite(t[i]) || t[i] < 0 || (i && !(t[i] > t[i - 1])))
                refuse(at + ": keyframe time " + std::to_string(i) + " is not finite, negative or not after the last");
        return t;
    }

    const tinygltf::Accessor &used(int accessor, const std::string &at, bool draco)
    {
        check_index(accessor, model.accessors.size(), at, "accessors", false);
        const tinygltf::Accessor &a = model.accessors[accessor];
        if (!draco && a.bufferView < 0)
            refuse(at + ": accessors[" + std::to_string(accessor) + "].bufferView missing");
        return a;
    }

    // One channel of a translation, rotation or scale into the scene; false: ignored.
    bool channel(const tinygltf::Animation &anim, const tinygltf::AnimationChannel &ch, const std::string &at)
    {
        check_index(ch.sampler, anim.samplers.size(), at + ".sampler", "samplers", false);
        if (ch.target_node < 0)
            return false;
        check_index(ch.target_node, model.nodes.size(), at + ".target.node", "nodes", false);
        int object = node_object[ch.target_node];
        const std::string &path = ch.target_path;
        int comps = path == "rotation" ? 4 : 3;
        if (object < 0 || model.nodes[ch.target_node].matrix.size() == 16 ||
            (path != "translation" && path != "rotation" && path != "scale"))
            return false;
        const tinygltf::AnimationSampler &sm = anim.samplers[ch.sampler];
        std::string sat = at + ".sampler";
        std::vector<float> times = key_times(sm.input, sat + ".input"), values;
        const tinygltf::Accessor &o = used(sm.output, sat + ".output", false);
        bool cubic = sm.interpolation == "CUBICSPLINE";
        if (o.type != (comps == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3) || o.count != times.size() * (cubic ? 3 : 1))
            refuse(sat + ".output: accessors[" + std::to_string(sm.output) + "] must hold " +
                   std::to_string(times.size() * (cubic ? 3 : 1)) + (comps == 4 ? " VEC4" : " VEC3") + " values");
        read_floats(sm.output, comps, &values);
        scene_anim_channel c = {object, path == "translation" ? SCENE_ANIM_TRANSLATION
                                        : comps == 4        ? SCENE_ANIM_ROTATION
                                                            : SCENE_ANIM_SCALE,
                                sm.interpolation == "STEP", times.size(), nullptr, nullptr};
        // not xalloc: a file's key count: the import refuses the file, never exits
        c.times = (float *)std::malloc(times.size() * sizeof(float));
        c.values = (float *)std::malloc(times.size() * (size_t)comps * sizeof(float));
        if (!c.times || !c.values) {
            std::free(c.times);
            std::free(c.values);
            refuse("out of memory");
        }
        std::memcpy(c.times, times.data(), times.size() * sizeof(float));
        for (size_t k = 0; k < times.size(); k++) // a cubic key: in-tangent, value, out-tangent
            for (int j = 0; j < comps; j++) {
                float v = values[(cubic ? 3 * k + 1 : k) * (size_t)comps + (size_t)j];
                if (!std::isfinite(v))
                    refuse(sat + ".output: value " + std::to_string(k) + " is not finite");
                c.values[k * (size_t)comps + (size_t)j] = v;
            }
        if (scene_add_anim_channel(out, &c) != 0) {
            std::free(c.times);
            std::free(c.values);
            refuse("out of memory");
        }
        return true;
    }

    void animations()
    {
        for (size_t a = 0; a < model.animations.size(); a++) {
            const tinygltf::Animation &anim = model.animations[a];
            for (size_t c = 0; c < anim.channels.size(); c++)
                if (!channel(anim, anim.channels[c], item(item("animations", a) + ".channels", c)))
                    channels_ignored++;
        }
    }

    void run()
    {
        materials();
        node_object.assign(model.nodes.size(), -1);
        holds.assign(model.nodes.size(), -1);
        roots();
        scene_end_object(out, -1);
        animations();
        if (objects_dropped)
            notes.push_back("more than " + std::to_string(SCENE_MAX_OBJECTS) + " nodes with meshes: " +
                            std::to_string(objects_dropped) + " move with their parents only");
        if (channels_ignored)
            notes.push_back(std::to_string(channels_ignored) + " animation channels ignored (morph weights, "
                            "nodes without meshes or given by a matrix)");
        if (out->camera_count > 0) // the file's first camera is the view
            out->camera = out->cameras[0];
        if (vertex_colours)
            notes.push_back("vertex colours (COLOR_0) ignored");
        if (lights_dropped)
            notes.push_back("more than " + std::to_string(SCENE_MAX_LIGHTS) + " lights: " +
                            std::to_string(lights_dropped) + " ignored");
    }

    void roots()
    {
        if (model.scenes.empty()) { // no scenes: every node that is nobody's child is a root
            std::vector<bool> child(model.nodes.size(), false);
            for (const tinygltf::Node &n : model.nodes)
                for (int c : n.children)
                    child[c] = true;
            for (size_t n = 0; n < model.nodes.size(); n++)
                if (!child[n])
                    node((int)n, identity(), -1);
            return;
        }
        for (int n : model.scenes[model.defaultScene >= 0 ? model.defaultScene : 0].nodes)
            node(n, identity(), -1);
    }
};

// The uri a refused path came from, by its JSON path (buffers[i].uri or images[i].uri).
std::string uri_field(const jvalue &root, const std::string &uri)
{
    for (const char *array : {"buffers", "images"}) {
        auto a = root.find(array);
        if (a == root.end())
            continue;
        for (size_t i = 0; i < a->size(); i++) {
            auto u = (*a)[i].find("uri");
            if (u != (*a)[i].end() && u->get<std::string>() == uri)
                return item(array, i) + ".uri";
        }
    }
    return "uri";
}

// tinygltf's parse and buffer loads, under the scene folder's file policy.
void load(const std::vector<unsigned char> &bytes, const char *path, const jvalue &root,
          bool allow_outside, tinygltf::Model *model)
{
    file_policy fp;
    const char *slash = std::strrchr(path, '/');
    fp.folder = slash ? std::string(path, slash == path ? 1 : (size_t)(slash - path)) : ".";
    char real[PATH_MAX];
    if (!realpath(fp.folder.c_str(), real))
        refuse("cannot resolve its folder (" + std::string(std::strerror(errno)) + ")");
    fp.root = std::string(real) + (real[std::strlen(real) - 1] == '/' ? "" : "/");
    fp.allow_outside = allow_outside;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({fs_exists, fs_expand, fs_read, fs_write, &fp});
    loader.SetImageLoader(keep_encoded, nullptr);
    std::string error, warning;
    bool ok = is_glb(bytes)
                  ? loader.LoadBinaryFromMemory(model, &error, &warning, bytes.data(),
                                                (unsigned)bytes.size(), fp.folder)
                  : loader.LoadASCIIFromString(model, &error, &warning,
                                               reinterpret_cast<const char *>(bytes.data()),
                                               (unsigned)bytes.size(), fp.folder);
    if (!fp.refused.empty())
        refuse(uri_field(root, fp.refused) + " \"" + fp.refused.substr(0, 80) +
               "\" is outside the scene file's folder (--allow-outside-paths allows it)");
    if (!ok) {
        // tinygltf's messages span lines; keep the first, without what a file's size was.
        std::string first = error.substr(0, error.find('\n'));
        first = first.substr(0, first.find(", but got"));
        refuse("cannot load glTF (" + (first.empty() ? std::string("unreadable file") : first) + ")");
    }
}

void put_le32(unsigned char *p, uint32_t v)
{
    for (int k = 0; k < 4; k++)
        p[k] = (unsigned char)(v >> (8 * k));
}

// tinygltf insists that an indices accessor has a bufferView, which a Draco primitive's
// need not have (Draco holds the faces): such primitives go to tinygltf without indices.
bool drop_draco_indices(jvalue *root)
{
    bool changed = false;
    auto meshes = root->find("meshes");
    for (size_t m = 0; meshes != root->end() && m < meshes->size(); m++) {
        auto prims = (*meshes)[m].find("primitives");
        for (size_t p = 0; prims != (*meshes)[m].end() && p < prims->size(); p++) {
            jvalue &prim = (*prims)[p];
            auto ext = prim.find("extensions");
            if (ext != prim.end() && ext->contains("KHR_draco_mesh_compression") && prim.erase("indices"))
                changed = true;
        }
    }
    return changed;
}

// The file's bytes with its JSON replaced (a GLB keeps its BIN chunk).
std::vector<unsigned char> with_json(const std::vector<unsigned char> &bytes, std::string text)
{
    if (!is_glb(bytes))
        return std::vector<unsigned char>(text.begin(), text.end());
    while (text.size() % 4)
        text += ' ';
    size_t rest = 20 + (size_t)le32(bytes.data() + 12);
    std::vector<unsigned char> out(20 + text.size() + (bytes.size() - rest));
    std::memcpy(out.data(), bytes.data(), 8);
    put_le32(out.data() + 8, (uint32_t)out.size());
    put_le32(out.data() + 12, (uint32_t)text.size());
    put_le32(out.data() + 16, 0x4E4F534Au);
    std::memcpy(out.data() + 20, text.data(), text.size());
    std::memcpy(out.data() + 20 + text.size(), bytes.data() + rest, bytes.size() - rest);
    return out;
}

std::string joined(const std::vector<std::string> &notes)
{
    std::string s;
    for (const std::string &n : notes)
        s += (s.empty() ? "" : "; ") + n;
    return s;
}

} // namespace

extern "C" int gltf_import(const char *path, int allow_outside_paths, scene *out, char *err,
                           size_t errlen)
{
    try {
        std::vector<unsigned char> bytes;
        std::string why;
        if (!read_regular(path, &bytes, &why))
            refuse("cannot read it (" + why + ")");
        jvalue root = parse_json(json_text(bytes));
        check_version(root);
        check_types(root);
        std::vector<std::string> notes;
        check_extensions(root, &notes);
        jvalue given = root;
        if (drop_draco_indices(&given))
            bytes = with_json(bytes, given.dump());
        tinygltf::Model model;
        load(bytes, path, root, allow_outside_paths != 0, &model);
        validator{model}.run();
        importer{model, out, notes, {}, {}, -1, false, 0, {}, {}, 0, 0}.run();
        std::snprintf(out->warning, sizeof out->warning, "%s", joined(notes).c_str());
    } catch (const std::exception &e) {
        std::snprintf(err, errlen, "scene %s: %s", path, e.what());
        return -1;
    }
    return 0;
}
