#pragma once

#include <tissuefem/base/parallel.h>

namespace tissuefem::time
{
  /// The locally owned entries of a distributed vector, for the entry-wise
  /// updates of methods with lumped (diagonal) masses.
  inline double *
  local_entries(VectorType &v)
  {
    return v.trilinos_vector()[0];
  }

  inline const double *
  local_entries(const VectorType &v)
  {
    return v.trilinos_vector()[0];
  }

  inline unsigned int
  local_size(const VectorType &v)
  {
    return v.locally_owned_size();
  }
} // namespace tissuefem::time
