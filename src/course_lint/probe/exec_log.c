/* course-lint's exec log: which programs the reference's lint run started (docs/course_lint.md,
 * "How not run is measured"). The package course_lint_probe, which course-lint adds to the
 * reference it grades, builds this as a library and names it in LD_AUDIT through its environment
 * hook, which only the student's processes of that run get. The dynamic linker then loads it into
 * every dynamically linked program they start, and calls la_preinit once the program is loaded,
 * before its own code runs; a C++ node started, then killed, is recorded all the same.
 *
 * Each record is one line, appended to $COURSE_LINT_DATA/exec.<pid namespace>.<pid>.<uid>:
 *     exec <TAB> pid namespace <TAB> pid <TAB> /proc/self/exe <TAB> argv, the words split by 0x1f
 * (a process that execs another program appends a second record to the same file). */
#define _GNU_SOURCE
#include <fcntl.h>
#include <link.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

unsigned int la_version(unsigned int version)
{
    (void)version;
    return LAV_CURRENT;
}

static unsigned long pid_namespace(void)
{
    char link[64];
    ssize_t n = readlink("/proc/self/ns/pid", link, sizeof link - 1);
    if (n <= 0)
        return 0;
    link[n] = '\0';
    char *open = strchr(link, '[');
    return open ? strtoul(open + 1, NULL, 10) : 0;
}

void la_preinit(uintptr_t *cookie)
{
    (void)cookie;
    const char *folder = getenv("COURSE_LINT_DATA");
    if (folder == NULL || folder[0] == '\0')
        return;
    char exe[4096];
    ssize_t length = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (length < 0)
        return;
    exe[length] = '\0';
    char argv[8192];
    ssize_t size = 0;
    int fd = open("/proc/self/cmdline", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        size = read(fd, argv, sizeof argv - 1);
        close(fd);
    }
    if (size < 0)
        size = 0;
    if (size > 0 && argv[size - 1] == '\0')
        size--;
    for (ssize_t i = 0; i < size; i++)
        if (argv[i] == '\0')
            argv[i] = '\x1f';
        else if (argv[i] == '\n' || argv[i] == '\t')
            argv[i] = ' ';
    argv[size] = '\0';
    unsigned long ns = pid_namespace();
    char path[4096];
    snprintf(path, sizeof path, "%s/exec.%lu.%d.%d", folder, ns, (int)getpid(), (int)getuid());
    char record[12800];
    int n = snprintf(record, sizeof record, "exec\t%lu\t%d\t%s\t%s\n", ns, (int)getpid(), exe, argv);
    if (n <= 0)
        return;
    if (n >= (int)sizeof record)
        n = (int)sizeof record - 1;
    fd = open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0)
        return;
    ssize_t written = write(fd, record, (size_t)n);
    (void)written;
    close(fd);
}
