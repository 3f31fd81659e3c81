/* session_keys: the keys a session adds after the built-in ones (the core keys and every
 * setting, gi_params_schema()), in the one order the master and every node use: the
 * scene's objects (cluster/scene_keys.h), then the application's (app_host.h). Equal
 * scenes and equal application builds give equal schemas, and HELLO's hash tells. */
#ifndef CAVELIGHT_SESSION_KEYS_H
#define CAVELIGHT_SESSION_KEYS_H

#include <stddef.h>

#include "app/app_host.h"
#include "cluster/scene_keys.h"

/* app may be NULL (no application). Returns 0, or -1 with one line in err. */
int session_keys_add(params_schema *schema, const scene *s, scene_keys *objects, app_host *app, char *err,
                     size_t errlen);

#endif
