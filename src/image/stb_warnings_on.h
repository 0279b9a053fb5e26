// After one of stb's implementations: our warnings again (stb_warnings_off.h).
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
