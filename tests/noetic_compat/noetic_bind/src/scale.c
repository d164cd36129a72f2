#include <limits.h>
#include "scale.h"

#ifdef __cplusplus
#error "scale.c must be compiled as C"
#endif

int scale_value(int value, int factor)
{
  long long product = (long long)value * (long long)factor;
  if (product > INT_MAX) return INT_MAX;
  if (product < INT_MIN) return INT_MIN;
  return (int)product;
}
