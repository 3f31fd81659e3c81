/* cavelight-node: a render node. Cluster mode: see cluster_node.h. */
#include <stdio.h>

#include "cluster_node.h"

int main(int argc, char **argv)
{
    if (cluster_node_wanted(argc, argv))
        return cluster_node_main(argc, argv);
    fprintf(stderr, "usage: cavelight-node --cluster FILE --name NODE [options]\n");
    return 2;
}
