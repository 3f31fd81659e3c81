/* node_cli: cavelight-node's command line, one option table for both modes.
 *
 * The table (node_cli.c) feeds getopt_long and --help (base/cli.h). --standalone fills a
 * node_options for standalone_run(); --cluster FILE --name NODE fills a cluster_node_desc
 * for cluster_node_start(). An option of the other mode is refused naming the mode where
 * it works. Adding an option is one table row and one case in set(). */
#ifndef CAVELIGHT_NODE_CLI_H
#define CAVELIGHT_NODE_CLI_H

#include "base/cli.h"
#include "cluster_node.h"
#include "standalone.h"

typedef enum node_mode {
    NODE_MODE_STANDALONE = 0,
    NODE_MODE_CLUSTER = 1,
} node_mode;

typedef struct node_cli {
    node_mode mode;
    node_options standalone;  /* --standalone */
    const char *config_path;  /* --cluster FILE */
    cluster_node_desc cluster;
} node_cli;

/* CLI_OK, CLI_HELP (help printed: exit 0) or CLI_ERROR (one line printed: exit 2). */
cli_result node_cli_parse(int argc, char **argv, node_cli *out);

#endif
