/* libFuzzer target: any bytes as a cluster message (what a stranger or a broken peer can
 * send to the master or a node) through wire_decode() and, for SNAPSHOT and FRAME, the
 * parameters through params_apply(); the same bytes also go to params_apply() directly
 * (after a u64 version), since the CRC keeps mutations from reaching it through a message.
 * A decoded message must encode again; applied parameters must encode to themselves.
 * Built with clang -fsanitize=fuzzer,address,undefined by CMake when clang is present. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cluster/params.h"
#include "cluster/wire.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* params as a valid message could carry them: onto a fresh store and onto one holding the
 * defaults, with the same verdict; what applies encodes and decodes to itself. */
static void apply(uint64_t version, const uint8_t *params, size_t len)
{
    static uint8_t enc[PARAMS_ENCODED_MAX];
    static params_store fresh, seeded, copy;
    static params_schema schema; /* the core keys and the frame settings */
    if (!schema.count)
        params_schema_init(&schema);
    params_init(&fresh, &schema);
    params_init(&seeded, &schema);
    params_commit(&seeded);
    int ok = params_apply(&fresh, version, params, len) == 0;
    if (ok != (params_apply(&seeded, version, params, len) == 0))
        abort();
    if (!ok)
        return;
    size_t n = params_encode_snapshot(&fresh, enc, sizeof enc);
    params_init(&copy, &schema);
    if (n == 0 || params_apply(&copy, fresh.version, enc, n) != 0 ||
        params_checksum(&copy) != params_checksum(&fresh))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t again[WIRE_MAX_MESSAGE];
    wire_msg m;
    if (wire_decode(data, size, &m) == WIRE_OK) {
        if (m.params_len > size || wire_encode(&m, again, sizeof again) == 0)
            abort(); /* what decodes must be a message the encoder accepts */
        if (m.type == WIRE_SNAPSHOT || m.type == WIRE_FRAME)
            apply(m.version, m.params, m.params_len);
    }
    /* The CRC keeps mutated messages out of params_apply(): feed it the bytes directly. */
    if (size > 8) {
        uint64_t version;
        memcpy(&version, data, sizeof version);
        apply(version, data + 8, size - 8);
    }
    return 0;
}
