// A declaration of the part of libmodal_pipe's server API that voxl-hitl-vio-server calls, as
// libmodal_pipe's modal_pipe_common.h and modal_pipe_server.h declare it (2025), written for a
// compile check: target/vio-server/pipe_server_libmodal_pipe.cpp is built against this in every
// build, so the code for boards with the library is compiled even where the library is absent.
// Nothing links against it; the real header and library replace it when the build finds them.
#pragma once

#ifdef __cplusplus
extern "C" {
#endif

#define MODAL_PIPE_MAX_DIR_LEN 64
#define MODAL_PIPE_MAX_NAME_LEN 32
#define MODAL_PIPE_MAX_TYPE_LEN 32
#define MODAL_PIPE_DEFAULT_PIPE_SIZE (1024 * 1024)

typedef struct pipe_info_t {
  char name[MODAL_PIPE_MAX_NAME_LEN];
  char location[MODAL_PIPE_MAX_DIR_LEN];
  char type[MODAL_PIPE_MAX_TYPE_LEN];
  char server_name[MODAL_PIPE_MAX_NAME_LEN];
  int size_bytes;
  int server_pid;
} pipe_info_t;

#define PIPE_INFO_INITIALIZER                                                                  \
  {                                                                                            \
    .name = "unknown", .location = "unknown", .type = "unknown", .server_name = "unknown",     \
    .size_bytes = MODAL_PIPE_DEFAULT_PIPE_SIZE, .server_pid = 0                                \
  }

int pipe_server_create(int ch, pipe_info_t info, int flags);
int pipe_server_write(int ch, const void* data, int bytes);
int pipe_server_get_num_clients(int ch);
void pipe_server_close(int ch);

#ifdef __cplusplus
}
#endif
