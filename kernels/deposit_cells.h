/* The cells of the deposit accumulator, one per vertex (deposition.cl adds to them, diffusion_decay.cl
 * empties them into the field): 64-bit fixed point, or floats on devices without
 * cl_khr_int64_base_atomics (built with PHYSARUM_FLOAT_DEPOSITS). */
#ifndef PHYSARUM_DEPOSIT_CELLS_H
#define PHYSARUM_DEPOSIT_CELLS_H

#ifdef PHYSARUM_FLOAT_DEPOSITS
typedef float PhysarumDepositCell;
#else
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
typedef long PhysarumDepositCell;
#endif

#endif /* PHYSARUM_DEPOSIT_CELLS_H */
