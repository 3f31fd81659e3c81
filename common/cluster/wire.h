/* wire: the binary messages between master and nodes (one ZeroMQ frame each).
 *
 * Header, 16 bytes little-endian: magic "CVLT", protocol version u16, type u16, payload
 * length u32, CRC-32 (IEEE) of the first 12 header bytes followed by the payload.
 * Payloads:
 *   HELLO     name, hash u64 (the config's and the parameter schema's,
 *             params_session_hash()), version the sender holds u64
 *   SNAPSHOT  version u64, params encoding (all keys)
 *   FRAME     version u64, base version u64, params delta (keys changed after base)
 *   READY     name, version u64, the frame's GI checksum u64, timings 4 x f32 (ms)
 *   SWAP      version u64
 *   BYE       name, reason u32
 *   HEARTBEAT name, version u64
 *   REFUSE    name, what u32 (wire_refuse_what), version u64, why: u16 length and
 *             0..WIRE_TEXT_MAX printable ASCII characters (a node that cannot take the
 *             scene or a version's parameters tells the master why)
 * A name is a u8 length and 1..WIRE_NAME_MAX bytes of [A-Za-z0-9_.-].
 * wire_decode() checks everything (size, magic, version, type, length, CRC, payload
 * layout, name characters) and never reads outside the buffer; params point into it. */
#ifndef CAVELIGHT_WIRE_H
#define CAVELIGHT_WIRE_H

#include <stddef.h>
#include <stdint.h>

enum {
    WIRE_MAGIC = 0x544c5643u, /* "CVLT" as little-endian bytes */
    WIRE_PROTOCOL = 6,        /* 2: the store's gi, pattern and light type keys; 3: vpl_count,
                                 vpl_seed; 4: vpl_selection; 5: REFUSE; 6: keys from a
                                 schema (every GI setting), HELLO's hash covers it */
    WIRE_HEADER_SIZE = 16,
    WIRE_NAME_MAX = 32,
    WIRE_TEXT_MAX = 300,      /* REFUSE's why */
    WIRE_MAX_PAYLOAD = 65536, /* a snapshot of a full store (PARAMS_ENCODED_MAX) fits */
    WIRE_MAX_MESSAGE = WIRE_HEADER_SIZE + WIRE_MAX_PAYLOAD,
    /* The longest a connection may take to finish its ZMTP (and CURVE) handshake, on both
     * ends (ZMQ_HANDSHAKE_IVL): a node's takes milliseconds, and libzmq's default of 30 s
     * let a stranger's unfinished handshakes hold the master's descriptors. */
    WIRE_HANDSHAKE_MS = 2000,
};

typedef enum wire_type {
    WIRE_HELLO = 1,
    WIRE_SNAPSHOT,
    WIRE_FRAME,
    WIRE_READY,
    WIRE_SWAP,
    WIRE_BYE,
    WIRE_HEARTBEAT,
    WIRE_REFUSE,
    WIRE_TYPE_END
} wire_type;

typedef enum wire_error {
    WIRE_OK = 0,
    WIRE_E_SHORT,     /* shorter than a header */
    WIRE_E_MAGIC,
    WIRE_E_PROTOCOL,  /* another protocol version */
    WIRE_E_TYPE,
    WIRE_E_LENGTH,    /* payload length disagrees with the frame, or too large */
    WIRE_E_CHECKSUM,
    WIRE_E_PAYLOAD,   /* payload does not match its type's layout */
    WIRE_E_COUNT
} wire_error;

/* BYE reasons. */
typedef enum wire_bye_reason {
    WIRE_BYE_SHUTDOWN = 1,        /* master is stopping the session */
    WIRE_BYE_DROPPED = 2,         /* master dropped the node (barrier timeout): say HELLO again */
    WIRE_BYE_CONFIG_MISMATCH = 3, /* HELLO carried another config hash */
    WIRE_BYE_LEAVING = 4,         /* node is exiting */
} wire_bye_reason;

/* What a node refuses (REFUSE). */
typedef enum wire_refuse_what {
    WIRE_REFUSE_SCENE = 1,  /* it cannot load or draw the scene: it leaves */
    WIRE_REFUSE_PARAMS = 2, /* a snapshot or frame whose values it cannot take (version) */
} wire_refuse_what;

typedef enum wire_timing {
    WIRE_TIMING_APPLY = 0, /* applying the delta */
    WIRE_TIMING_FRAME,     /* frame pass: RSM, injection, propagation */
    WIRE_TIMING_EYES,      /* all eye passes */
    WIRE_TIMING_TOTAL,     /* FRAME received to READY sent */
    WIRE_TIMING_COUNT
} wire_timing;

typedef struct wire_msg {
    wire_type type;
    char name[WIRE_NAME_MAX + 1]; /* HELLO, READY, BYE, HEARTBEAT, REFUSE */
    uint64_t version;             /* every type but BYE */
    uint64_t base_version;        /* FRAME */
    uint64_t config_hash;         /* HELLO */
    uint64_t checksum;            /* READY */
    float timings[WIRE_TIMING_COUNT]; /* READY */
    uint32_t reason;              /* BYE: wire_bye_reason; REFUSE: wire_refuse_what */
    char text[WIRE_TEXT_MAX + 1]; /* REFUSE: why, printable ASCII */
    const uint8_t *params;        /* SNAPSHOT, FRAME */
    size_t params_len;
} wire_msg;

uint32_t wire_crc32(const void *data, size_t len);
/* Returns the message size, or 0 when it does not fit cap or a field is invalid. */
size_t wire_encode(const wire_msg *m, uint8_t *buf, size_t cap);
wire_error wire_decode(const uint8_t *buf, size_t len, wire_msg *out);
const char *wire_error_string(wire_error e);
const char *wire_type_name(int type);
/* 1 when name is 1..WIRE_NAME_MAX characters of [A-Za-z0-9_.-]. */
int wire_name_valid(const char *name);

#endif
