/* src/clrt_cache.c -- see clrt_cache.h. Stages: the key and the entry's path (clrt_cache_find); the entry read,
 * checked and built (clrt_cache_load); a program to save held back (clrt_cache_store), then handed to a detached
 * process that writes the entry and trims the directory (clrt_cache_save_deferred). */
#define _GNU_SOURCE /* mkostemp, utimensat, nice */
#include "clrt_cache.h"
#include "clrt_pocl.h"
#include "iacsg.h"
#include "detach.h"
#include "digest.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Format 2: PoCL's binaries without their bitcode (src/clrt_pocl.h); the key hashes it, so format 1's entries are
 * never looked up again and age out of the directory. */
#define CACHE_MAGIC "iacsg program binary 2\n"
enum { CACHE_MAX_BYTES = 256 << 20, CACHE_MAX_FILES = 4096 };

typedef struct {
    char magic[sizeof CACHE_MAGIC];
    char key[65];
    char binary_sha[65];
    unsigned long long size;
} entry_header;

static void hash_string(digest_ctx *c, const char *s) { digest_update(c, s, strlen(s) + 1); }

static void hash_device_info(digest_ctx *c, cl_device_id d, cl_device_info what) {
    char buf[1024] = "";
    clGetDeviceInfo(d, what, sizeof buf - 1, buf, NULL);
    hash_string(c, buf);
}

/* mkdir -p with mode 0700 for what it makes; 0 when the directory exists at the end. */
static int make_dirs(char *path) {
    for (char *p = path + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            int r = mkdir(path, 0700);
            *p = '/';
            if (r != 0 && errno != EEXIST)
                return -1;
        }
    return mkdir(path, 0700) == 0 || errno == EEXIST ? 0 : -1;
}

static int cache_dir(char *dir, size_t size) {
    const char *off = getenv("IACSG_KERNEL_CACHE");
    if (off && strcmp(off, "0") == 0)
        return -1;
    const char *own = getenv("IACSG_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (own && *own)
        n = snprintf(dir, size, "%s/programs", own);
    else if (xdg && *xdg == '/')
        n = snprintf(dir, size, "%s/iacsg/programs", xdg);
    else if (home && *home == '/')
        n = snprintf(dir, size, "%s/.cache/iacsg/programs", home);
    else
        return -1;
    return n > 0 && (size_t)n < size - 80 ? 0 : -1;
}

void clrt_cache_find(const clrt *rt, const char *const *sources, size_t count, const char *options,
                     clrt_cache_entry *entry) {
    entry->path[0] = '\0';
    char dir[sizeof entry->path];
    if (cache_dir(dir, sizeof dir) != 0)
        return;
    digest_ctx c;
    digest_init(&c);
    hash_string(&c, CACHE_MAGIC);
    hash_string(&c, iacsg_version());
    hash_string(&c, rt->platform_name);
    char version[1024] = "";
    clGetPlatformInfo(rt->platform, CL_PLATFORM_VERSION, sizeof version - 1, version, NULL);
    hash_string(&c, version);
    hash_device_info(&c, rt->device, CL_DEVICE_NAME);
    hash_device_info(&c, rt->device, CL_DEVICE_VERSION);
    hash_device_info(&c, rt->device, CL_DRIVER_VERSION);
    hash_string(&c, options ? options : "");
    unsigned long long n = count;
    digest_update(&c, &n, sizeof n);
    for (size_t k = 0; k < count; k++) {
        n = strlen(sources[k]); /* with each length, so that no two splits of the text meet */
        digest_update(&c, &n, sizeof n);
        digest_update(&c, sources[k], n);
    }
    char key[65];
    digest_hex(&c, key);
    size_t len = strlen(dir); /* cache_dir left room for the name */
    dir[len] = '/';
    memcpy(dir + len + 1, key, 64);
    memcpy(dir + len + 65, ".bin", 5);
    memcpy(entry->path, dir, sizeof entry->path);
}

/* The entry's binary, checked against its header, or NULL (*damaged: there is a file, and it is not one). */
static unsigned char *read_entry(const clrt_cache_entry *entry, size_t *size, int *damaged) {
    FILE *f = fopen(entry->path, "rb");
    *damaged = 0;
    if (!f)
        return NULL;
    entry_header h;
    unsigned char *bin = NULL;
    const char *name = strrchr(entry->path, '/') + 1;
    if (fread(&h, sizeof h, 1, f) == 1 && memcmp(h.magic, CACHE_MAGIC, sizeof h.magic) == 0 &&
        h.key[64] == '\0' && strncmp(name, h.key, 64) == 0 && h.binary_sha[64] == '\0' && h.size > 0 &&
        h.size < (1ull << 32) && (bin = malloc(h.size))) {
        digest_ctx c;
        char sha[65];
        digest_init(&c);
        if (fread(bin, 1, h.size, f) == h.size && fgetc(f) == EOF) {
            digest_update(&c, bin, h.size);
            digest_hex(&c, sha);
        } else {
            sha[0] = '\0';
        }
        if (strcmp(sha, h.binary_sha) != 0) {
            free(bin);
            bin = NULL;
        }
    }
    fclose(f);
    *size = bin ? h.size : 0;
    *damaged = !bin;
    return bin;
}

cl_program clrt_cache_load(const clrt *rt, const clrt_cache_entry *entry, const char *options) {
    if (!entry->path[0])
        return NULL;
    size_t size;
    int damaged;
    unsigned char *bin = read_entry(entry, &size, &damaged);
    if (!bin) {
        if (damaged)
            unlink(entry->path); /* the build from source writes it anew */
        return NULL;
    }
    cl_int rc = CL_SUCCESS, status = CL_SUCCESS;
    const unsigned char *bins[1] = {bin};
    cl_program p = clCreateProgramWithBinary(rt->context, 1, &rt->device, &size, bins, &status, &rc);
    free(bin);
    if (p && (rc != CL_SUCCESS || status != CL_SUCCESS ||
              clBuildProgram(p, 1, &rt->device, options, NULL, NULL) != CL_SUCCESS)) {
        clReleaseProgram(p);
        p = NULL;
    }
    if (!p)
        unlink(entry->path); /* refused by the driver (another driver build, say) */
    else
        utimensat(AT_FDCWD, entry->path, NULL, 0); /* its mtime says when it was last used: see trim */
    return p;
}

typedef struct {
    char name[80];
    time_t used;
    off_t size;
} entry_file;

static int older(const void *a, const void *b) {
    time_t x = ((const entry_file *)a)->used, y = ((const entry_file *)b)->used;
    return (x > y) - (x < y);
}

/* Removes the least recently used files while the directory holds more than CACHE_MAX_BYTES or CACHE_MAX_FILES. */
static void trim(const char *dir) {
    DIR *d = opendir(dir);
    if (!d)
        return;
    entry_file *files = NULL;
    size_t n = 0, cap = 0;
    long long total = 0;
    for (struct dirent *e; (e = readdir(d));) {
        struct stat st;
        size_t len = strlen(e->d_name);
        int entry = len > 4 && strcmp(e->d_name + len - 4, ".bin") == 0;
        int marker = len > 5 && strcmp(e->d_name + len - 5, ".seen") == 0;
        if (!(entry || marker) || len >= sizeof files->name || fstatat(dirfd(d), e->d_name, &st, 0) != 0)
            continue;
        if (n == cap) {
            entry_file *grown = realloc(files, (cap = cap ? 2 * cap : 64) * sizeof *files);
            if (!grown)
                break;
            files = grown;
        }
        memcpy(files[n].name, e->d_name, len + 1);
        files[n].used = st.st_mtime;
        files[n++].size = st.st_size;
        total += st.st_size;
    }
    if (total > CACHE_MAX_BYTES || n > CACHE_MAX_FILES) {
        qsort(files, n, sizeof *files, older);
        for (size_t k = 0; k < n && (total > CACHE_MAX_BYTES || n - k > CACHE_MAX_FILES); k++)
            if (unlinkat(dirfd(d), files[k].name, 0) == 0)
                total -= files[k].size;
    }
    free(files);
    closedir(d);
}

/* Whether the entry's program was built before (its marker, KEY.seen, exists); makes the marker if not. Where
 * the driver compiles at the first launch, only a program built a second time is saved: PoCL compiles every
 * kernel of the program anew for a binary (for any work-group size), which cost ~4 s for the reference view's
 * program, more than the 2-3 s of its first build, and would double the first run of every expression tried
 * once. */
static int seen_before(const char *path, const char *dir) {
    char marker[sizeof ((clrt_cache_entry *)0)->path + 8];
    snprintf(marker, sizeof marker, "%.*s.seen", (int)(strlen(path) - 4), path);
    if (unlink(marker) == 0)
        return 1;
    char made[sizeof marker];
    snprintf(made, sizeof made, "%s", dir);
    int fd = make_dirs(made) == 0 ? open(marker, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600) : -1;
    if (fd >= 0) {
        close(fd);
        trim(dir);
    }
    return 0;
}

/* Writes the program's binary as the entry (the binary's query is what costs), PoCL's without its bitcode. */
static void save(const clrt_cache_entry *entry, cl_program program) {
    char dir[sizeof entry->path];
    snprintf(dir, sizeof dir, "%s", entry->path);
    *strrchr(dir, '/') = '\0';
    size_t size = 0;
    if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL) != CL_SUCCESS || size == 0)
        return;
    unsigned char *bin = malloc(size);
    unsigned char *bins[1] = {bin};
    char tmp[sizeof entry->path + 16];
    snprintf(tmp, sizeof tmp, "%s.tmp-XXXXXX", entry->path);
    int fd = -1;
    if (bin && clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof bins, bins, NULL) == CL_SUCCESS &&
        make_dirs(dir) == 0 && (fd = mkostemp(tmp, O_CLOEXEC)) >= 0) {
        size = clrt_pocl_binary_without_ir(bin, size);
        entry_header h;
        memset(&h, 0, sizeof h);
        memcpy(h.magic, CACHE_MAGIC, sizeof h.magic);
        memcpy(h.key, strrchr(entry->path, '/') + 1, 64);
        digest_ctx c;
        digest_init(&c);
        digest_update(&c, bin, size);
        digest_hex(&c, h.binary_sha);
        h.size = size;
        FILE *f = fdopen(fd, "wb");
        int ok = f && fwrite(&h, sizeof h, 1, f) == 1 && fwrite(bin, 1, size, f) == size;
        ok = f ? fclose(f) == 0 && ok : (close(fd), 0);
        if (!ok || rename(tmp, entry->path) != 0)
            unlink(tmp);
        else
            trim(dir);
    }
    free(bin);
}

/* The saves clrt_cache_defer_saves holds back, their programs retained. */
enum { MAX_DEFERRED = 8 };
static struct {
    int on, count;
    clrt_cache_entry entries[MAX_DEFERRED];
    cl_program programs[MAX_DEFERRED];
} deferred;

void clrt_cache_store(const clrt_cache_entry *entry, cl_program program, int compiled) {
    if (!entry->path[0] || !deferred.on)
        return;
    char dir[sizeof entry->path];
    snprintf(dir, sizeof dir, "%s", entry->path);
    *strrchr(dir, '/') = '\0';
    if ((compiled || seen_before(entry->path, dir)) && deferred.count < MAX_DEFERRED &&
        clRetainProgram(program) == CL_SUCCESS) {
        deferred.entries[deferred.count] = *entry;
        deferred.programs[deferred.count++] = program;
    }
}

void clrt_cache_defer_saves(void) { deferred.on = 1; }

void clrt_cache_save_deferred(void) {
    if (deferred.count == 0)
        return;
    const char *mode = getenv("IACSG_CACHE_SAVE");
    if (mode && strcmp(mode, "wait") == 0) { /* for scripts that time the runs after this one (make bench) */
        for (int k = 0; k < deferred.count; k++)
            save(&deferred.entries[k], deferred.programs[k]);
        return;
    }
    if (detach_process(NULL) == 1) { /* the saver: no child of the command, holding none of its descriptors */
        int niced = nice(19); /* it yields the CPUs to the commands that follow */
        (void)niced;
        alarm(600); /* a saver stuck in the driver after the fork ends anyway */
        for (int k = 0; k < deferred.count; k++)
            save(&deferred.entries[k], deferred.programs[k]);
        _exit(0);
    }
    for (int k = 0; k < deferred.count; k++)
        clReleaseProgram(deferred.programs[k]);
    deferred.count = 0;
}
