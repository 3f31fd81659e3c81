/* input_config: the sources an input config names, made into an input handle (the
 * factory), or a recording to play back.
 *
 * An input config (JSON, configs/input/, docs/input.md) holds "sources", each with its
 * "type" (dtrack, vrpn, usb, desk, playback), an optional "name" and the type's own keys,
 * and optionally "record". input_open() reads and validates the whole config first (one
 * line naming the file and the field on a fault), then opens every source and adds it to
 * a new handle (input.h). Keys no part of the config reads are warned with the nearest
 * valid key, or refused with input_desc.strict. input_config_check() does the reading and
 * validating without opening anything (cavelight-master --check). */
#ifndef CAVELIGHT_INPUT_CONFIG_H
#define CAVELIGHT_INPUT_CONFIG_H

#include <stddef.h>

#include "input.h"

/* Returns NULL with a one-line reason in err. */
input *input_open(const input_desc *desc, char *err, size_t errlen);

/* Reads and validates desc->path (a config or a recording) and opens nothing. Returns 0,
 * or -1 with the first fault in err; every unknown key goes to desc->warn (or stderr)
 * and, with desc->strict, makes it -1 too. */
int input_config_check(const input_desc *desc, char *err, size_t errlen);

#endif
