/* check: cavelight-master --check, a cluster config validated without starting anything.
 *
 * Reads the config (as a session would: every field's range), then checks, each problem
 * one line on stderr: keys that no section reads (with the nearest valid key), the scene
 * (loaded, as every node will load it; --scene overrides the config's), every node's host
 * (its name resolves), the CurveZMQ keys the master needs (curve mode), and the input
 * config (--input: read and validated, no source opened). It binds no socket, starts no
 * node and opens no device or window. Each check is one row of a table in check.c: a new
 * part of the config (a warp file, say) adds its row there. */
#ifndef CAVELIGHT_CHECK_H
#define CAVELIGHT_CHECK_H

#include "master_cli.h"

/* Returns the exit code: 0 when the config passes every check, 2 when not (one line per
 * problem printed). */
int check_run(const master_options *o);

#endif
