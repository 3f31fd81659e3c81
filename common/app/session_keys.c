/* session_keys: objects' keys, then the application's (session_keys.h). */
#include "app/session_keys.h"

int session_keys_add(params_schema *schema, const scene *s, scene_keys *objects, app_host *app, char *err,
                     size_t errlen)
{
    if (scene_keys_add(schema, s, objects, err, errlen) != 0)
        return -1;
    return app ? app_host_add_keys(app, schema, err, errlen) : 0;
}
