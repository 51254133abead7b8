/* src/cli_main.c -- the `iacsg` command: hands a command that needs OpenCL to the launcher (src/cli_launch.c), or
 * dispatches to a subcommand (src/cli.h), or renders. */
#include "cli.h"
#include "cli_brlcad.h"
#include "cli_launch.h"
#include "iacsg.h"
#include <stdio.h>
#include <string.h>

static const char usage[] =
    "usage: iacsg EXPR|SCENE [options]    render an implicit solid (f < 0 inside) to an image\n"
    "       iacsg eval EXPR [options]     evaluate the expression's enclosure over a box on the host\n"
    "       iacsg compile EXPR            print the OpenCL C the compiler emits for it\n"
    "       iacsg view EXPR|SCENE [options]  open a window on it (see Viewer below)\n"
    "       iacsg MODEL.asc [OBJECT ...] [options]  render a BRL-CAD model's objects (see BRL-CAD models below)\n"
    "       iacsg objects MODEL.asc       list the model's top objects (those no combination references)\n"
    "       iacsg regions MODEL.asc [OBJECT ...]  print each region's index (as -ids writes it), id and path\n"
    "       iacsg devices                 list the OpenCL devices (numbers for -device)\n"
    "       iacsg --help | --version\n"
    "\n"
    "EXPR is an expression in x, y, z (and t), e.g. \"min(sphere, torus)\"; SCENE is the name of a scene file.\n"
    "\n"
    "Render options (defaults in brackets):\n"
    "  -o FILE            output image; the format follows the extension: png, exr, tif, jpg, ... [iacsg.png]\n"
    "  -size WxH          image size in pixels [1024x1024]\n"
    "  -eps E             width of the bisection's leaves along the ray, in world units [2^-16]\n"
    "  -bounds X0,Y0,Z0,X1,Y1,Z1\n"
    "                     the box rays are clipped to [a box proven to enclose the surface (a scene with\n"
    "                     regions: its solids) when the compiler finds one, else -2,-2,-2,2,2,2; the\n"
    "                     command says which]\n"
    "  -eye X,Y,Z         eye position [placed by -az/-el]\n"
    "  -at X,Y,Z          point looked at [centre of the bounds]\n"
    "  -up X,Y,Z          up direction [0,0,1]\n"
    "  -fov DEG           vertical field of view [40]\n"
    "  -az DEG -el DEG    place the eye the BRL-CAD way, azimuth from +x towards +y and elevation above the\n"
    "                     xy plane, far enough to see the whole bounds [35, 25]\n"
    "  -ortho HEIGHT      orthographic view, HEIGHT world units high [perspective]\n"
    "  -depth FILE        also write the depth: float32, one channel, distance from the eye along the ray,\n"
    "                     +inf where the ray misses\n"
    "  -normals FILE      also write the unit normals: float32, three channels, 0 where the ray misses\n"
    "  -ids FILE          also write the id of the region or surface hit (numbered in declaration order):\n"
    "                     float32, one channel, -1 where the ray hits none (an expression: 0 where it hits)\n"
    "  -time T            value of the variable t, the real the decimal denotes (enclosed) [0]\n"
    "  -frames N          render N frames for t = 0, 1/N, ..., (N-1)/N into numbered files (name_0000.png)\n"
    "  -fp64              double precision intervals and rays [float]\n"
    "  -fast              no outward rounding, the same algorithm otherwise: NOT rigorous, may miss surfaces; for\n"
    "                     measuring the cost of the rounding\n"
    "  -tape auto|on|off  the expression interpreted from a tape by one program built once for all expressions\n"
    "                     (on), or compiled to its own OpenCL C (off); auto interprets expressions of 1024\n"
    "                     operations or more and unions of 128 parts or more, where the compile takes seconds,\n"
    "                     unless effects are asked for [auto]\n"
    "  -device N          OpenCL device number, see `iacsg devices` [0; under mpirun the rank's number on its\n"
    "                     node, modulo the count of devices]\n"
    "  -resume            skip the frames whose files are all there (an image is only renamed into place once\n"
    "                     complete), so that a job stopped halfway is finished by the same command\n"
    "  -stats             print rays, interval evaluations per ray (mean, max), kernel build, render and write\n"
    "                     time; for regions also segments and partitions per ray, overlaps, per-ray buffer\n"
    "                     bytes; with effects, the secondary rays and their evaluations per ray\n"
    "\n";

/* The rest of the help, apart: ISO C bounds a string literal's length. */
static const char usage_more[] =
    "Effects (each pixel shaded on the device from its hits; secondary rays traced by the same bisection):\n"
    "  -shade MODE        lit, gradient (the normal's direction as colour, lit), normals, depth, ids [lit]\n"
    "  -background R,G,B[,R,G,B]  the background colour, or a gradient top to bottom, in [0, 1] [grey-blue]\n"
    "  -light KIND,X,Y,Z,I  point,X,Y,Z,I (a point light) or dir,X,Y,Z,I (towards the light) of intensity I;\n"
    "                     repeatable, up to 8 [the scene's light statements, else a key and a fill light]\n"
    "  -shadows           a shadow ray from each lit hit to each light\n"
    "  -bounces N         reflected rays a path may take (0 to 16) [2]\n"
    "  -reflect K         the expression's material reflects K of the light (scenes: material reflect K) [0]\n"
    "  -opacity A         the expression is transparent: each crossing of its surface a layer of opacity A [1]\n"
    "  -aa N              N x N rays in the pixels whose centre rays differ from a neighbour's (-depth,\n"
    "                     -normals, -ids stay the centre ray's; an expression's from N = 3: the corners\n"
    "                     first, the rest where they differ) [1]\n"
    "\n"
    "Camera: f = normalize(at - eye), r = normalize(f x up), u = r x f. Pixel (i, j), i left to right and j top\n"
    "to bottom, looks along normalize(f + s r + v u) with s = (2(i+1/2)/W - 1) tan(fov/2) W/H and\n"
    "v = (1 - 2(j+1/2)/H) tan(fov/2). With -ortho the ray starts at eye + s r + v u (tan(fov/2) replaced by\n"
    "HEIGHT/2) and goes along f. Only t >= 0 is traced.\n"
    "\n"
    "Under mpirun (mpirun -np N iacsg ...), the ranks share the work: with -frames each rank takes the next frame\n"
    "when it is done with its last; without, they share the rows of the one frame in bands and rank 0 writes it.\n"
    "\n"
    "Guarantees (without -fast): a surface (or region) that a pixel's ray crosses inside the bounds is never\n"
    "missed, and the depth is never after the ray's first root (the region's first point) there.\n"
    "\n"
    "Viewer: iacsg view takes the render options but -depth, -normals and -frames; -size is the window's size,\n"
    "-o names the screenshots (numbered: iacsg_0000.png, ...). Drag to orbit about the point looked at, wheel to\n"
    "zoom, right-drag or shift-drag to pan; it renders at a quarter of the resolution while the view moves. Keys:\n"
    "  r reset the view    [ ] halve, double eps    a antialiasing (2x2 rays a pixel) on/off\n"
    "  1 2 3 4 show colour, depth, normals, ids    s save a screenshot    q, Esc quit\n"
    "  p print the iacsg command line that renders this view to the same image\n"
    "A scene file is reloaded when it changes; an error in it is shown in the title and on stderr, and the last\n"
    "good scene stays. The title shows the frame time and interval evaluations per ray. Needs a display (X11 or\n"
    "Wayland) and SDL2 (libsdl2-2.0-0), which only the viewer loads.\n"
    "\n"
    "BRL-CAD models: a .asc database (v4 or v5, as g2asc writes it) renders its named top objects, by default\n"
    "those no combination references, with librt's regions: booleans above region level pushed down, a region\n"
    "invented for a solid no region holds, air regions left out, one solid per distinct (name, matrix). Primitives\n"
    "read: arb8 (and arb4-7), tgc (rcc, rec, trc, tec), ell (sph), tor, half, pipe, ehy; any other, a dangling\n"
    "member, a cycle or a malformed line is refused with its line. Colours: the combination's, else the colour\n"
    "table's, else the palette. The view defaults to rt's: orthographic (-ortho the bounds' diagonal, unless\n"
    "-ortho or -fov is given), -az 35 -el 25, centred on the bounds, which are rt's model box; lengths in mm.\n"
    "\n";

/* The environment's variables, apart for the same reason. */
static const char usage_environment[] =
    "Environment:\n"
    "  IACSG_LAUNCH_IDLE=S  a render or `devices` runs in a process forked by the launcher, which has loaded the\n"
    "                     OpenCL driver and stays for S seconds without a command [30]; 0: the command runs itself\n"
    "  IACSG_WRITER_IDLE=S  the image writer (a process that has loaded OpenImageIO) stays for S seconds without\n"
    "                     a command, for the next commands of this user and build [30]; 0: a writer per command\n"
    "  IACSG_CACHE_DIR=DIR  where built OpenCL programs are kept (DIR/programs, at most 256 MB)\n"
    "                     [$XDG_CACHE_HOME/iacsg, else ~/.cache/iacsg]; IACSG_KERNEL_CACHE=0: not kept;\n"
    "                     IACSG_CACHE_SAVE=wait: a program is saved before the command ends, not after it\n";

int cli_dispatch(int argc, char **argv) {
    if (argc < 2) {
        fputs(usage, stderr);
        fputs(usage_more, stderr);
        fputs(usage_environment, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "-help") == 0) {
        fputs(usage, stdout);
        fputs(usage_more, stdout);
        fputs(usage_environment, stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("iacsg %s\n", IACSG_VERSION);
        return 0;
    }
    if (strcmp(cmd, "eval") == 0)
        return cli_eval(argc - 1, argv + 1);
    if (strcmp(cmd, "compile") == 0)
        return cli_compile(argc - 1, argv + 1);
    if (strcmp(cmd, "view") == 0)
        return cli_view(argc - 1, argv + 1);
    if (strcmp(cmd, "objects") == 0)
        return cli_objects(argc - 1, argv + 1);
    if (strcmp(cmd, "regions") == 0)
        return cli_regions(argc - 1, argv + 1);
    if (strcmp(cmd, "devices") == 0)
        return cli_devices(argc - 1, argv + 1);
    return cli_render(argc, argv);
}

int main(int argc, char **argv) {
    int status;
    if (cli_launch(argc, argv, &status))
        return status;
    return cli_dispatch(argc, argv);
}
