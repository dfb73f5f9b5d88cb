set(ZP_PLATFORM_SYSTEM_LAYER windows)
set(ZP_PLATFORM_COMPILE_DEFINITIONS
    ZENOH_WINDOWS
    _CRT_SECURE_NO_WARNINGS)
set(ZP_PLATFORM_SOURCE_FILES
    "${PROJECT_SOURCE_DIR}/src/system/windows/system.c"
    "${PROJECT_SOURCE_DIR}/src/system/windows/network.c"
    "${PROJECT_SOURCE_DIR}/src/link/transport/tcp/tcp_windows.c"
    "${PROJECT_SOURCE_DIR}/src/link/transport/udp/udp_windows.c")
if(ZP_UDP_MULTICAST_ENABLED)
  list(APPEND ZP_PLATFORM_SOURCE_FILES
       "${PROJECT_SOURCE_DIR}/src/link/transport/udp/udp_multicast_windows.c")
endif()
set(ZP_PLATFORM_LINK_LIBRARIES Ws2_32 Iphlpapi)
