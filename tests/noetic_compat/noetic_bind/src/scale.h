#ifndef NOETIC_BIND_SCALE_H
#define NOETIC_BIND_SCALE_H
#ifdef __cplusplus
extern "C" {
#endif
/* value * factor, saturated to the int range. */
int scale_value(int value, int factor);
#ifdef __cplusplus
}
#endif
#endif
