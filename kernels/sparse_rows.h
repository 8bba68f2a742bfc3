/* Rows of a CSR matrix times a vector, shared by diffusion_decay.cl and conjugate_gradients.cl. */
#ifndef PHYSARUM_SPARSE_ROWS_H
#define PHYSARUM_SPARSE_ROWS_H

/* (A x)_i for a CSR matrix: the loop is bounded by the row's length. */
float csr_row_times(const uint i, __global const int* row_start, __global const int* column,
                    __global const float* value, __global const float* x) {
  float sum = 0.0f;
  const int end = row_start[i + 1];
  for (int k = row_start[i]; k < end; ++k) sum += value[k] * x[column[k]];
  return sum;
}

#endif /* PHYSARUM_SPARSE_ROWS_H */
