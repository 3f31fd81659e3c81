/* cavelight-node: a render node. `--standalone` renders without a master and writes
 * images and a timing report (standalone.h); --cluster runs the master's FRAME/SWAP loop
 * (cluster_node.h). One option table for both (node_cli.h). */
#include "node_cli.h"

int main(int argc, char **argv)
{
    static node_cli cli;
    switch (node_cli_parse(argc, argv, &cli)) {
    case CLI_HELP: return 0;
    case CLI_ERROR: return 2;
    default: break;
    }
    if (cli.mode == NODE_MODE_CLUSTER)
        return cluster_node_start(cli.config_path, &cli.cluster);
    return standalone_run(&cli.standalone);
}
