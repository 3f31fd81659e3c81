/* gpu_checksum: buffer ranges summed on the GPU, read back late (gpu_checksum.h). */
#include <stdlib.h>

#include "base/xalloc.h"
#include "gltools.h"
#include "gpu_checksum.h"

enum { SLOTS = 2, GROUP = 256 };

struct gpu_checksum {
    const gl_functions *gl;
    GLuint program, sums;     /* sums: SLOTS pairs of words, mapped for good */
    volatile GLuint *mapped;
    GLsync fence[SLOTS];      /* the slot's frame submitted, not yet read */
    int submitted[SLOTS];     /* a frame was submitted there (with parts or without) */
    uint64_t last;            /* the value of the last submitted frame read */
    int slot;                 /* the frame being recorded */
    int parts;                /* added to it */
    GLint loc[6];             /* u_offset, u_count, u_salt, u_slot, u_width, u_stride */
};

gpu_checksum *gpu_checksum_create(const gl_functions *gl, char *err, size_t errlen)
{
    const char *comp = "checksum.comp";
    GLuint prog = gltools_compute_parts(gl, &comp, 1, NULL, err, errlen);
    if (!prog)
        return NULL;
    gpu_checksum *c = xcalloc(1, sizeof *c);
    c->gl = gl;
    c->program = prog;
    const char *names[6] = {"u_offset", "u_count", "u_salt", "u_slot", "u_width", "u_stride"};
    for (int i = 0; i < 6; i++)
        c->loc[i] = gl->GetUniformLocation(prog, names[i]);
    GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    const GLuint zero[2 * SLOTS] = {0};
    gl->GenBuffers(1, &c->sums);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->sums);
    gl->BufferStorage(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, flags);
    c->mapped = gl->MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, flags);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return c;
}

void gpu_checksum_destroy(gpu_checksum *c)
{
    if (!c)
        return;
    for (int i = 0; i < SLOTS; i++)
        if (c->fence[i])
            c->gl->DeleteSync(c->fence[i]);
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->sums);
    c->gl->UnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    c->gl->DeleteBuffers(1, &c->sums);
    c->gl->DeleteProgram(c->program);
    free(c);
}

/* Slot s's value once its fence is signalled: the GPU finished it a frame ago as a rule,
 * so this waits only when the GPU runs more than a frame behind. */
static void resolve(gpu_checksum *c, int s)
{
    if (!c->submitted[s])
        return;
    c->submitted[s] = 0;
    c->last = 0;
    if (!c->fence[s])
        return; /* no parts */
    while (c->gl->ClientWaitSync(c->fence[s], GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull) ==
           GL_TIMEOUT_EXPIRED)
        ;
    c->gl->DeleteSync(c->fence[s]);
    c->fence[s] = 0;
    c->last = (uint64_t)c->mapped[2 * s] | (uint64_t)c->mapped[2 * s + 1] << 32;
}

uint64_t gpu_checksum_frame(gpu_checksum *c)
{
    if (!c)
        return 0;
    resolve(c, c->slot);
    c->slot = (c->slot + 1) % SLOTS;
    c->mapped[2 * c->slot] = c->mapped[2 * c->slot + 1] = 0;
    c->parts = 0;
    return c->last;
}

void gpu_checksum_add(gpu_checksum *c, GLuint buffer, size_t offset_words, size_t records,
                      int width, int stride)
{
    size_t count_words = records * (size_t)width;
    if (!c || count_words == 0)
        return;
    const gl_functions *gl = c->gl;
    gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gl->UseProgram(c->program);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, c->sums);
    const int v[6] = {(int)offset_words, (int)count_words, c->parts++, c->slot, width, stride};
    for (int i = 0; i < 6; i++)
        gl->Uniform1i(c->loc[i], v[i]);
    gl->DispatchCompute((GLuint)((count_words + GROUP - 1) / GROUP), 1, 1);
}

void gpu_checksum_submit(gpu_checksum *c)
{
    if (!c)
        return;
    c->submitted[c->slot] = 1;
    if (c->parts == 0)
        return;
    c->gl->MemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    c->fence[c->slot] = c->gl->FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}
