/* gpu.h - `cacao-inspect gpu`: what a GPU compiler makes of the embedded permutations (registers,
 * spills, occupancy, ACO's cycle estimates) and the estimated frame cost of configurations beside
 * AMD FidelityFX CACAO's. The model without a device is gpu_model.h; docs/gpu.md has the figures. */
#ifndef CACAO_INSPECT_GPU_H
#define CACAO_INSPECT_GPU_H

#include <stdio.h>

/* Runs the subcommand on argv (the words after "gpu"); returns the exit status. */
int inspect_gpu(int argc, char **argv);

/* Its usage lines. */
void inspect_gpu_usage(FILE *out);

#endif /* CACAO_INSPECT_GPU_H */
