#include "cluster/wire.h"

#include "base/byteorder.h"

#include <string.h>
#include <zlib.h>

/* zlib's crc32 is the IEEE 802.3 CRC-32 (reflected, polynomial 0xEDB88320) the header
 * names. */
uint32_t wire_crc32(const void *data, size_t len)
{
    return (uint32_t)crc32_z(0L, data, len);
}

/* CRC of header bytes 0..11 followed by the payload (the CRC field itself is skipped). */
static uint32_t crc_message(const uint8_t *msg, size_t payload_len)
{
    uLong c = crc32_z(0L, msg, 12);
    return (uint32_t)crc32_z(c, msg + WIRE_HEADER_SIZE, payload_len);
}

int wire_name_valid(const char *name)
{
    size_t n = 0;
    for (; name[n]; n++) {
        char c = name[n];
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                 c == '_' || c == '.' || c == '-';
        if (!ok || n >= WIRE_NAME_MAX)
            return 0;
    }
    return n > 0;
}

/* Bounded writer and reader: every access checks the remaining room first. */
typedef struct cursor {
    uint8_t *w;
    const uint8_t *r;
    size_t pos, cap;
    int bad;
} cursor;

static void put(cursor *c, uint64_t v, int bytes)
{
    if (c->bad || c->cap - c->pos < (size_t)bytes) {
        c->bad = 1;
        return;
    }
    le_put(c->w + c->pos, v, bytes);
    c->pos += (size_t)bytes;
}

static void put_bytes(cursor *c, const void *p, size_t n)
{
    if (c->bad || c->cap - c->pos < n) {
        c->bad = 1;
        return;
    }
    if (n)
        memcpy(c->w + c->pos, p, n);
    c->pos += n;
}

static void put_name(cursor *c, const char *name)
{
    if (!wire_name_valid(name)) {
        c->bad = 1;
        return;
    }
    size_t n = strlen(name);
    put(c, n, 1);
    put_bytes(c, name, n);
}

/* REFUSE's text: printable ASCII only, so that a peer's text cannot forge log lines. */
static int text_valid(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (s[i] < 0x20 || s[i] > 0x7e)
            return 0;
    return n <= WIRE_TEXT_MAX;
}

static void put_text(cursor *c, const char *text)
{
    size_t n = strnlen(text, WIRE_TEXT_MAX + 1);
    if (!text_valid(text, n)) {
        c->bad = 1;
        return;
    }
    put(c, n, 2);
    put_bytes(c, text, n);
}

static uint64_t get(cursor *c, int bytes)
{
    if (c->bad || c->cap - c->pos < (size_t)bytes) {
        c->bad = 1;
        return 0;
    }
    uint64_t v = le_get(c->r + c->pos, bytes);
    c->pos += (size_t)bytes;
    return v;
}

static void get_name(cursor *c, char *out)
{
    size_t n = (size_t)get(c, 1);
    if (c->bad || n == 0 || n > WIRE_NAME_MAX || c->cap - c->pos < n) {
        c->bad = 1;
        return;
    }
    memcpy(out, c->r + c->pos, n);
    out[n] = 0;
    c->pos += n;
    if (!wire_name_valid(out))
        c->bad = 1;
}

static void get_text(cursor *c, char *out)
{
    size_t n = (size_t)get(c, 2);
    if (c->bad || n > WIRE_TEXT_MAX || c->cap - c->pos < n || !text_valid((const char *)c->r + c->pos, n)) {
        c->bad = 1;
        return;
    }
    memcpy(out, c->r + c->pos, n);
    out[n] = 0;
    c->pos += n;
}

static void put_f32(cursor *c, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put(c, u, 4);
}

static float get_f32(cursor *c)
{
    uint32_t u = (uint32_t)get(c, 4);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

size_t wire_encode(const wire_msg *m, uint8_t *buf, size_t cap)
{
    if (cap < WIRE_HEADER_SIZE)
        return 0;
    cursor c = {.w = buf, .pos = WIRE_HEADER_SIZE, .cap = cap < WIRE_MAX_MESSAGE ? cap : WIRE_MAX_MESSAGE};
    switch (m->type) {
    case WIRE_HELLO:
        put_name(&c, m->name);
        put(&c, m->config_hash, 8);
        put(&c, m->version, 8);
        break;
    case WIRE_SNAPSHOT:
        put(&c, m->version, 8);
        put(&c, m->params_len, 4);
        put_bytes(&c, m->params, m->params_len);
        break;
    case WIRE_FRAME:
        put(&c, m->version, 8);
        put(&c, m->base_version, 8);
        put(&c, m->params_len, 4);
        put_bytes(&c, m->params, m->params_len);
        break;
    case WIRE_READY:
        put_name(&c, m->name);
        put(&c, m->version, 8);
        put(&c, m->checksum, 8);
        for (int i = 0; i < WIRE_TIMING_COUNT; i++)
            put_f32(&c, m->timings[i]);
        break;
    case WIRE_SWAP:
        put(&c, m->version, 8);
        break;
    case WIRE_BYE:
        put_name(&c, m->name);
        put(&c, m->reason, 4);
        break;
    case WIRE_HEARTBEAT:
        put_name(&c, m->name);
        put(&c, m->version, 8);
        break;
    case WIRE_REFUSE:
        put_name(&c, m->name);
        put(&c, m->reason, 4);
        put(&c, m->version, 8);
        put_text(&c, m->text);
        break;
    default:
        return 0;
    }
    if (c.bad)
        return 0;
    size_t payload = c.pos - WIRE_HEADER_SIZE;
    cursor h = {.w = buf, .cap = WIRE_HEADER_SIZE};
    put(&h, WIRE_MAGIC, 4);
    put(&h, WIRE_PROTOCOL, 2);
    put(&h, (uint64_t)m->type, 2);
    put(&h, payload, 4);
    put(&h, crc_message(buf, payload), 4);
    return c.pos;
}

wire_error wire_decode(const uint8_t *buf, size_t len, wire_msg *out)
{
    memset(out, 0, sizeof *out);
    if (len < WIRE_HEADER_SIZE)
        return WIRE_E_SHORT;
    cursor h = {.r = buf, .cap = WIRE_HEADER_SIZE};
    uint32_t magic = (uint32_t)get(&h, 4);
    uint16_t protocol = (uint16_t)get(&h, 2);
    uint16_t type = (uint16_t)get(&h, 2);
    uint32_t payload = (uint32_t)get(&h, 4);
    uint32_t crc = (uint32_t)get(&h, 4);
    if (magic != WIRE_MAGIC)
        return WIRE_E_MAGIC;
    if (protocol != WIRE_PROTOCOL)
        return WIRE_E_PROTOCOL;
    if (type < WIRE_HELLO || type >= WIRE_TYPE_END)
        return WIRE_E_TYPE;
    if (payload > WIRE_MAX_PAYLOAD || payload != len - WIRE_HEADER_SIZE)
        return WIRE_E_LENGTH;
    if (crc != crc_message(buf, payload))
        return WIRE_E_CHECKSUM;

    cursor c = {.r = buf, .pos = WIRE_HEADER_SIZE, .cap = len};
    out->type = (wire_type)type;
    switch (out->type) {
    case WIRE_HELLO:
        get_name(&c, out->name);
        out->config_hash = get(&c, 8);
        out->version = get(&c, 8);
        break;
    case WIRE_SNAPSHOT:
    case WIRE_FRAME:
        out->version = get(&c, 8);
        if (type == WIRE_FRAME)
            out->base_version = get(&c, 8);
        out->params_len = (size_t)get(&c, 4);
        if (!c.bad && out->params_len != len - c.pos)
            c.bad = 1;
        if (!c.bad) {
            out->params = buf + c.pos;
            c.pos += out->params_len;
        }
        break;
    case WIRE_READY:
        get_name(&c, out->name);
        out->version = get(&c, 8);
        out->checksum = get(&c, 8);
        for (int i = 0; i < WIRE_TIMING_COUNT; i++)
            out->timings[i] = get_f32(&c);
        break;
    case WIRE_SWAP:
        out->version = get(&c, 8);
        break;
    case WIRE_BYE:
        get_name(&c, out->name);
        out->reason = (uint32_t)get(&c, 4);
        break;
    case WIRE_HEARTBEAT:
        get_name(&c, out->name);
        out->version = get(&c, 8);
        break;
    case WIRE_REFUSE:
        get_name(&c, out->name);
        out->reason = (uint32_t)get(&c, 4);
        out->version = get(&c, 8);
        get_text(&c, out->text);
        break;
    default:
        c.bad = 1;
    }
    if (c.bad || c.pos != len) {
        memset(out, 0, sizeof *out);
        return WIRE_E_PAYLOAD;
    }
    return WIRE_OK;
}

const char *wire_error_string(wire_error e)
{
    static const char *const s[WIRE_E_COUNT] = {
        "ok", "shorter than a header", "bad magic", "unknown protocol version",
        "unknown message type", "bad payload length", "checksum mismatch", "malformed payload",
    };
    return (unsigned)e < WIRE_E_COUNT ? s[e] : "?";
}

const char *wire_type_name(int type)
{
    static const char *const s[WIRE_TYPE_END] = {
        "?", "HELLO", "SNAPSHOT", "FRAME", "READY", "SWAP", "BYE", "HEARTBEAT", "REFUSE",
    };
    return type > 0 && type < WIRE_TYPE_END ? s[type] : "?";
}
