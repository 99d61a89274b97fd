// Runs MuJoCo functions so that a fatal MuJoCo error returns an error code instead of
// ending the process (robosuite-env/src/sim/guard.rs explains the design).
//
// MuJoCo reports a fatal error (for example "mj_stackAlloc: out of memory") through its log
// handler and must never continue after it: the handler may not return. Each rs_guard_*
// function installs a thread-local log handler, saves the context with sigsetjmp and calls
// MuJoCo; on an error the handler copies the message and siglongjmps back here. Between the
// sigsetjmp and the siglongjmp there are only C frames (this file and MuJoCo's own code,
// which installs no Rust callback in this project), so no Rust frame is ever skipped.
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stddef.h>
#include <string.h>

// The leading fields of MuJoCo 3.17's mjLogMessage (mujoco/mjtnum.h, mjLogMessage_); only
// these are read.
typedef struct {
  int level;
  int topic;
  char subject[1024];
  const char* body;
} rs_log_message;

typedef void (*rs_log_handler)(const rs_log_message*);
typedef void (*rs_mj_fn)(const void*, void*);

// MuJoCo's thread-local log handler (the one its Python bindings use for the same purpose);
// returns the previous thread-local handler.
extern rs_log_handler _mjPRIVATE_setTlsLogHandler(rs_log_handler handler);
extern void mj_step(const void* m, void* d);
extern void mj_step1(const void* m, void* d);
extern void mj_step2(const void* m, void* d);
extern void mj_forward(const void* m, void* d);
extern void* mj_makeData(const void* m);
extern void mj_deleteData(void* d);

enum { RS_LOG_WARNING = 2, RS_LOG_ERROR = 3 };

static _Thread_local sigjmp_buf rs_jump;
static _Thread_local char rs_error[2048];

static void rs_copy(char* out, size_t size, const rs_log_message* msg) {
  size_t n = strnlen(msg->subject, sizeof msg->subject);
  if (n >= size) n = size - 1;
  memcpy(out, msg->subject, n);
  out[n] = 0;
  if (msg->body && n + 2 < size) {
    out[n] = '\n';
    size_t m = strnlen(msg->body, size - n - 2);
    memcpy(out + n + 1, msg->body, m);
    out[n + 1 + m] = 0;
  }
}

// Errors jump back to the guarded call; warnings and info messages are dropped: the caller
// reads MuJoCo's warning counters (mjData.warning) instead, without printing.
static void rs_handler(const rs_log_message* msg) {
  if (msg->level >= RS_LOG_ERROR) {
    rs_copy(rs_error, sizeof rs_error, msg);
    siglongjmp(rs_jump, 1);
  }
}

static int rs_guarded(rs_mj_fn f, const void* m, void* d) {
  rs_log_handler previous = _mjPRIVATE_setTlsLogHandler(rs_handler);
  if (sigsetjmp(rs_jump, 0) != 0) {
    _mjPRIVATE_setTlsLogHandler(previous);
    return 1;
  }
  f(m, d);
  _mjPRIVATE_setTlsLogHandler(previous);
  return 0;
}

int rs_guard_step(const void* m, void* d) { return rs_guarded(mj_step, m, d); }
int rs_guard_step1(const void* m, void* d) { return rs_guarded(mj_step1, m, d); }
int rs_guard_step2(const void* m, void* d) { return rs_guarded(mj_step2, m, d); }
int rs_guard_forward(const void* m, void* d) { return rs_guarded(mj_forward, m, d); }

static void rs_make_and_delete(const void* m, void* unused) {
  (void)unused;
  void* d = mj_makeData(m);
  if (d) mj_deleteData(d);
}

// Allocates an mjData for the model and frees it again: 0 when that works, 1 after a
// fatal error (for example an arena too large to allocate).
int rs_guard_trial_make_data(const void* m) { return rs_guarded(rs_make_and_delete, m, NULL); }

// The message of the last fatal error on this thread (NUL-terminated).
const char* rs_guard_last_error(void) { return rs_error; }
