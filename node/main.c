/* cavelight-node: a render node. `--standalone` renders without a master and writes
 * images and a timing report (standalone.h); --cluster runs the master's FRAME/SWAP loop
 * (cluster_node.h). */
#include <stdio.h>

#include "cluster_node.h"
#include "standalone.h"

int main(int argc, char **argv)
{
    /* Cluster mode has its own options (cluster_node.h). */
    if (cluster_node_wanted(argc, argv))
        return cluster_node_main(argc, argv);
    node_options o;
    if (standalone_parse(argc, argv, &o) != 0)
        return 2;
    if (!o.standalone) {
        fprintf(stderr, "cavelight-node: no mode given: use --standalone, or --cluster FILE --name NODE\n");
        return 2;
    }
    return standalone_run(&o);
}
