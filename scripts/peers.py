#!/usr/bin/env python3
"""hrad beside two public hierarchical radiosity programs, on their own scenes, one core each.

  scripts/peers.py build SPLASH_RADIOSITY RPKCPP PEERS
      Copies SPLASH-2's radiosity (the folder apps/radiosity of github.com/ProfessorWest/splash2-posix) to
      PEERS/splash and rpkCpp (github.com/OscarChavarro/rpkCpp: src, etc, CMakeLists.txt) to PEERS/rpkCpp, adds to
      each a per-polygon dump of its answer (written only when SPLASH_DUMP / RPK_DUMP names a file), and builds
      both with plain -O2 (rpkCpp ships -O3 -ffast-math; its per-iteration print of the whole element hierarchy is
      kept behind RPK_PRINT_HIERARCHY, since printing megabytes is not solving). Nothing else in them changes.
  scripts/peers.py run PEERS [--hrad build/bin/hrad] [--repeats 3] [--work DIR] [--scenes a,b]
                             [--reuse-references | --reuse-rulers]
      For each scene: a converged hrad reference (and a check of it at a quarter of its elements), then every
      setting of every program run in turn, repeats times, pinned to core 0 (taskset), timed by CPU seconds
      (user + system, from wait4), each scored per input polygon against the reference. Prints one table
      (Markdown) and writes it with the raw runs to WORK (default /tmp/hrad-peers).

The scenes are notebooks_data/scenes/peers/ (their README gives where each comes from). SPLASH-2 solves its
built-in scenes (-batch, -batch -room), rpkCpp the MGF files in PEERS/rpkCpp/etc; the OBJ files are the same
polygons in the same order, which the scoring checks (count, areas and centroids of every polygon).

Error: per input polygon the reflected radiosity R = B - E (gray: the mean of the three channels), B the
polygon's area-weighted mean over its leaf elements; area-weighted relative L2 of R against the reference's, and
the bias of the area-weighted mean of R (negative: darker than the reference); and the L2 error against the
independent Monte Carlo ruler (hrad reference --faces), its own noise removed in quadrature.
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, 'notebooks_data', 'scenes', 'peers')

# ---- build ------------------------------------------------------------------------------------------------------

# SPLASH-2 (rad_main.c): after the batch statistics, one line per patch (its final triangles, after the BSP
# splits): area, centroid, reflectance, emittance, the area-weighted mean radiosity of its leaf elements, leaves.
SPLASH_DUMP = r'''
static FILE *hrad_dump_file ;
static double hrad_dump_sum[4] ;
static long hrad_dump_leaves ;
static void hrad_dump_leaf(Element *e, long unused, long process_id)
{
    hrad_dump_sum[0] += e->area * e->rad.r ; hrad_dump_sum[1] += e->area * e->rad.g ;
    hrad_dump_sum[2] += e->area * e->rad.b ; hrad_dump_sum[3] += e->area ; hrad_dump_leaves++ ;
}
static void hrad_dump_patch(Patch *p, long unused, long process_id)
{
    hrad_dump_sum[0] = hrad_dump_sum[1] = hrad_dump_sum[2] = hrad_dump_sum[3] = 0 ; hrad_dump_leaves = 0 ;
    foreach_leaf_element_in_patch( p, hrad_dump_leaf, 0, process_id ) ;
    fprintf( hrad_dump_file, "P %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %ld\n", p->area,
             (p->p1.x + p->p2.x + p->p3.x) / 3.0, (p->p1.y + p->p2.y + p->p3.y) / 3.0, (p->p1.z + p->p2.z + p->p3.z) / 3.0,
             p->color.r, p->color.g, p->color.b, p->emittance.r, p->emittance.g, p->emittance.b,
             hrad_dump_sum[0] / hrad_dump_sum[3], hrad_dump_sum[1] / hrad_dump_sum[3], hrad_dump_sum[2] / hrad_dump_sum[3],
             hrad_dump_leaves ) ;
}
static void hrad_dump(void)
{
    char *name = getenv( "SPLASH_DUMP" ) ;
    if( name == 0 || (hrad_dump_file = fopen( name, "w" )) == 0 ) return ;
    foreach_patch_in_bsp( hrad_dump_patch, 0, 0 ) ;
    fclose( hrad_dump_file ) ;
}

int main(int argc, char *argv[])
'''

# rpkCpp (src/app/batch.cpp): after the radiance iterations, one line per patch in the scene's order: area,
# centroid, Rd, pi Ed, pi times the area-weighted mean radiance of its leaf elements (an exitance), leaves.
RPK_DUMP = r'''
#include <cmath>
#include <cstdlib>
static void
hradDumpLeaves(const Element *e, double *sum, long *leaves) {
    if ( e->regularSubElements != nullptr ) {
        for ( int i = 0; i < 4; i++ ) {
            if ( e->regularSubElements[i] != nullptr ) {
                hradDumpLeaves(e->regularSubElements[i], sum, leaves);
            }
        }
        return;
    }
    sum[0] += e->area * e->radiance[0].r;
    sum[1] += e->area * e->radiance[0].g;
    sum[2] += e->area * e->radiance[0].b;
    sum[3] += e->area;
    ++*leaves;
}

static void
hradDump(const Scene *scene) {
    const char *name = getenv("RPK_DUMP");
    FILE *file = name != nullptr && scene->patchList != nullptr ? fopen(name, "w") : nullptr;
    if ( file == nullptr ) {
        return;
    }
    for ( int i = 0; i < scene->patchList->size(); i++ ) {
        const Patch *patch = scene->patchList->get(i);
        const Element *e = patch->radianceData;
        double sum[4] = {0.0, 0.0, 0.0, 0.0};
        double c[3] = {0.0, 0.0, 0.0};
        long leaves = 0;
        for ( int k = 0; k < patch->numberOfVertices; k++ ) {
            c[0] += patch->vertex[k]->point->x / patch->numberOfVertices;
            c[1] += patch->vertex[k]->point->y / patch->numberOfVertices;
            c[2] += patch->vertex[k]->point->z / patch->numberOfVertices;
        }
        if ( e != nullptr ) {
            hradDumpLeaves(e, sum, &leaves);
        }
        double a = sum[3] > 0.0 ? sum[3] : 1.0;
        fprintf(file, "P %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %ld\n", patch->area,
                c[0], c[1], c[2], e ? e->Rd.r : 0.0, e ? e->Rd.g : 0.0, e ? e->Rd.b : 0.0,
                e ? M_PI * e->Ed.r : 0.0, e ? M_PI * e->Ed.g : 0.0, e ? M_PI * e->Ed.b : 0.0,
                M_PI * sum[0] / a, M_PI * sum[1] / a, M_PI * sum[2] / a, leaves);
    }
    fclose(file);
}

void
batchExecuteRadianceSimulation('''


def edit(path, old, new, count=1):
    text = open(path).read()
    if old not in text:
        sys.exit('%s: the text to patch was not found (another version of the peer?): %r' % (path, old[:70]))
    open(path, 'w').write(text.replace(old, new, count))


def run_checked(cmd, cwd):
    print('+ (cd %s && %s)' % (cwd, ' '.join(cmd)), file=sys.stderr)
    subprocess.run(cmd, cwd=cwd, check=True)


def build(args):
    peers = os.path.abspath(args.peers)
    splash, rpk = os.path.join(peers, 'splash'), os.path.join(peers, 'rpkCpp')
    if os.path.exists(splash) or os.path.exists(rpk):
        sys.exit('%s: holds splash/ or rpkCpp/ already; build into an empty folder' % peers)
    if not os.path.isfile(os.path.join(args.splash, 'rad_main.c')):
        sys.exit('%s: no rad_main.c (give the folder apps/radiosity of splash2-posix)' % args.splash)
    if not os.path.isfile(os.path.join(args.rpk, 'src', 'app', 'batch.cpp')):
        sys.exit('%s: no src/app/batch.cpp (give a checkout of rpkCpp)' % args.rpk)
    shutil.copytree(args.splash, splash)
    for part in ('src', 'etc', 'CMakeLists.txt'):
        source = os.path.join(args.rpk, part)
        (shutil.copytree if os.path.isdir(source) else shutil.copy)(source, os.path.join(rpk, part))

    edit(splash + '/rad_main.c', '\nint main(int argc, char *argv[])\n', SPLASH_DUMP)
    edit(splash + '/rad_main.c', '            print_statistics( stdout, 0 ) ;\n        }\n    else',
         '            print_statistics( stdout, 0 ) ;\n            hrad_dump() ;\n        }\n    else')
    sources = sorted(f for d in ('.', 'glibdumb', 'glibps') for f in
                     (os.path.join(d, n) for n in os.listdir(os.path.join(splash, d))) if f.endswith('.c'))
    run_checked(['gcc', '-O2', '-w', '-Iglibdumb', '-Iglibps'] + sources + ['-lm', '-lpthread', '-o', 'radiosity'],
                splash)

    edit(rpk + '/CMakeLists.txt', 'add_compile_options(-ffast-math -O3)', 'add_compile_options(-O2)')
    edit(rpk + '/src/app/batch.cpp', '\nvoid\nbatchExecuteRadianceSimulation(', RPK_DUMP)
    edit(rpk + '/src/app/batch.cpp', '    printf("Computations finished.\\n");',
         '    if ( radianceMethod != nullptr ) {\n        hradDump(scene);\n    }\n    printf("Computations finished.\\n");')
    strategy = rpk + '/src/GALERKIN/processing/GatheringClusteredStrategy.cpp'
    edit(strategy, '    GalerkingElementDebug::printGalerkinElementHierarchy(galerkinState->topCluster, 0);\n',
         '    if ( getenv("RPK_PRINT_HIERARCHY") != nullptr ) {\n'
         '        GalerkingElementDebug::printGalerkinElementHierarchy(galerkinState->topCluster, 0);\n    }\n')
    edit(strategy, '#include', '#include <cstdlib>\n#include')
    os.makedirs(rpk + '/build')
    run_checked(['cmake', '..', '-DCMAKE_BUILD_TYPE=None'], rpk + '/build')
    run_checked(['cmake', '--build', '.', '-j', str(args.jobs)], rpk + '/build')
    print('built %s/radiosity and %s/build/rpk' % (splash, rpk))


# ---- run --------------------------------------------------------------------------------------------------------

# (scene, program, setting label, arguments). hrad's '--aeps' settings are fractions of the scene's total area
# (None: hrad's defaults). rpkCpp: its Galerkin solver, 11 iterations as its batch examples run it.
RPK = ['-raytracing-method', 'none', '-iterations', '11', '-radiance-method', 'Galerkin']
# hrad's most accurate options: linear elements, and sources refined below aeps where a receiver is near.
LINEAR_AUTO = ['--basis', 'linear', '--source-levels', 'auto']
SETTINGS = [
    ('splash_test', 'SPLASH-2', 'defaults', []),
    ('splash_test', 'SPLASH-2', '-ae 2000 -bf 0.005 -en 0.001', ['-ae', '2000', '-bf', '0.005', '-en', '0.001']),
    ('splash_test', 'hrad', 'aeps total/100', 1 / 100),
    ('splash_test', 'hrad', 'defaults', None),
    ('splash_test', 'hrad', 'aeps total/4000', 1 / 4000),
    ('splash_test', 'hrad', 'linear basis', (None, ['--basis', 'linear'])),
    ('splash_test', 'hrad', 'linear, source levels auto', (None, LINEAR_AUTO)),
    ('splash_room', 'SPLASH-2', 'defaults', []),
    ('splash_room', 'hrad', 'aeps total/250', 1 / 250),
    ('splash_room', 'hrad', 'linear, total/250, feps 0.03, 16 samples',
     (1 / 250, ['--basis', 'linear'] + ['--feps', '0.03', '--visibility-samples', '16'])),
    ('splash_room', 'hrad', 'linear, total/100, feps 0.04, 8 samples',
     (1 / 100, ['--basis', 'linear'] + ['--feps', '0.04', '--visibility-samples', '8'])),
    ('splash_room', 'hrad', 'defaults', None),
    ('splash_room', 'hrad', 'linear basis', (None, ['--basis', 'linear'])),
    ('splash_room', 'hrad', 'linear, source levels auto', (None, LINEAR_AUTO)),
    ('rpk_cube', 'rpkCpp', 'link error 1e-4', ['-gr-link-error-threshold', '1e-4']),
    ('rpk_cube', 'rpkCpp', 'defaults (1e-5)', []),
    ('rpk_cube', 'rpkCpp', 'link error 1e-6', ['-gr-link-error-threshold', '1e-6']),
    ('rpk_cube', 'rpkCpp', 'link error 1e-7', ['-gr-link-error-threshold', '1e-7']),
    ('rpk_cube', 'hrad', 'aeps total/100', 1 / 100),
    ('rpk_cube', 'hrad', 'linear, total/100, feps 0.06, 4 samples',
     (1 / 100, ['--basis', 'linear'] + ['--feps', '0.06', '--visibility-samples', '4'])),
    ('rpk_cube', 'hrad', 'linear, total/100, feps 0.04, 16 samples',
     (1 / 100, ['--basis', 'linear'] + ['--feps', '0.04', '--visibility-samples', '16'])),
    ('rpk_cube', 'hrad', 'linear, total/400, feps 0.04, 16 samples',
     (1 / 400, ['--basis', 'linear'] + ['--feps', '0.04', '--visibility-samples', '16'])),
    ('rpk_cube', 'hrad', 'defaults', None),
    ('rpk_cube', 'hrad', 'aeps total/4000', 1 / 4000),
    ('rpk_cube', 'hrad', 'linear basis', (None, ['--basis', 'linear'])),
    ('rpk_cube', 'hrad', 'linear, source levels auto', (None, LINEAR_AUTO)),
    ('rpk_office2', 'rpkCpp', 'link error 1e-4', ['-gr-link-error-threshold', '1e-4']),
    ('rpk_office2', 'rpkCpp', 'defaults (1e-5)', []),
    ('rpk_office2', 'rpkCpp', 'link error 1e-6', ['-gr-link-error-threshold', '1e-6']),
    ('rpk_office2', 'rpkCpp', 'link error 1e-7', ['-gr-link-error-threshold', '1e-7']),
    ('rpk_office2', 'hrad', 'aeps total/100', 1 / 100),
    ('rpk_office2', 'hrad', 'defaults', None),
    ('rpk_office2', 'hrad', 'source levels auto', (None, ['--source-levels', 'auto'])),
    ('rpk_office2', 'hrad', 'linear, total/50, feps 0.04, 4 samples',
     (1 / 50, ['--basis', 'linear'] + ['--feps', '0.04', '--visibility-samples', '4'])),
    ('rpk_office2', 'hrad', 'linear, feps 0.02, 16 samples',
     (None, ['--basis', 'linear'] + ['--feps', '0.02', '--visibility-samples', '16'])),
    ('rpk_office2', 'hrad', 'linear basis', (None, ['--basis', 'linear'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto, total/25, feps 0.06, 4 samples',
     (1 / 25, LINEAR_AUTO + ['--feps', '0.06', '--visibility-samples', '4'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto, total/50, feps 0.04, 4 samples',
     (1 / 50, LINEAR_AUTO + ['--feps', '0.04', '--visibility-samples', '4'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto, total/100, feps 0.04, 8 samples',
     (1 / 100, LINEAR_AUTO + ['--feps', '0.04', '--visibility-samples', '8'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto, total/200, feps 0.04, 16 samples',
     (1 / 200, LINEAR_AUTO + ['--feps', '0.04', '--visibility-samples', '16'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto, feps 0.02, 16 samples',
     (None, LINEAR_AUTO + ['--feps', '0.02', '--visibility-samples', '16'])),
    ('rpk_office2', 'hrad', 'linear, source levels auto', (None, LINEAR_AUTO)),
]
SPLASH_SCENE = {'splash_test': ['-batch'], 'splash_room': ['-batch', '-room']}
RPK_SCENE = {'rpk_cube': 'etc/cube.mgf', 'rpk_office2': 'etc/office2/office2.mgf'}
# The reference: hrad's most accurate setting (linear elements, sources refined below aeps where a receiver is
# near) with its smallest elements this fraction of the total area; its check uses 4x that.
REFERENCE_AEPS = 1 / 16000
REFERENCE_OPTIONS = LINEAR_AUTO
# Points per polygon of the independent Monte Carlo ruler (hrad reference --faces), which judges the reference.
RULER_SAMPLES = 65536


def read_obj_faces(path):
    """Area and centroid (vertex mean) of every face of an OBJ, in file order."""
    vertices, faces = [], []
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == 'v':
            vertices.append([float(x) for x in t[1:4]])
        elif t[0] == 'f':
            idx = [int(x.split('/')[0]) for x in t[1:]]
            pts = [vertices[i - 1] if i > 0 else vertices[i] for i in idx]
            n = [0.0, 0.0, 0.0]
            for k in range(len(pts)):  # Newell's normal: twice the vector area
                a, b = pts[k], pts[(k + 1) % len(pts)]
                n[0] += (a[1] - b[1]) * (a[2] + b[2])
                n[1] += (a[2] - b[2]) * (a[0] + b[0])
                n[2] += (a[0] - b[0]) * (a[1] + b[1])
            faces.append((0.5 * math.sqrt(sum(x * x for x in n)), [sum(p[c] for p in pts) / len(pts) for c in range(3)]))
    return faces


def gray(c):
    return sum(c) / 3.0


def read_answer(path):
    """(area, centroid or None, R = B - E gray) per polygon, from an hrad report or a peer's dump."""
    if path.endswith('.json'):
        return [(p['area'], None, gray(p['radiosity']) - gray(p['emission'])) for p in json.load(open(path))['patches']]
    rows = []
    for line in open(path):
        t = line.split()
        if t and t[0] == 'P':
            v = [float(x) for x in t[1:14]]
            rows.append((v[0], v[1:4], gray(v[10:13]) - gray(v[7:10])))
    return rows


def read_ruler(path, obj):
    """The ruler's answer (hrad reference --faces CSV) as read_answer's rows, and its noise in the same norm."""
    emission = [gray(p['emission']) for p in json.load(open(path.replace('.ruler.csv', '.reference.json')))['patches']]
    rows, var = [], 0.0
    with open(path) as f:
        header = f.readline().strip().split(',')
        for line, e in zip(f, emission):
            v = dict(zip(header, line.strip().split(',')))
            b = [float(v['radiosity_' + c]) for c in 'rgb']
            se = [float(v['radiosity_%s_se' % c]) for c in 'rgb']
            rows.append((float(v['area']), None, gray(b) - e))
            var += float(v['area']) * sum(x * x for x in se) / 9.0  # the channels' mean, independent errors
    den = sum(a * r * r for a, c, r in rows)
    return rows, math.sqrt(var / den)


def l2_error(rows, reference, faces, what):
    """Area-weighted relative L2 of R against the reference's (after checking the polygons are the OBJ's)."""
    return errors_against(rows, reference, faces, what)[0]


def errors_against(rows, reference, faces, what):
    """(relative L2, relative bias of the area-weighted mean) of R against the reference's."""
    if len(rows) != len(reference):
        sys.exit('%s: %d polygons, the reference %d' % (what, len(rows), len(reference)))
    # A peer's polygons must be the OBJ's faces in order (hrad's are by construction; it splits a non-planar
    # face, so its area may differ from the OBJ's Newell area in the fourth digit).
    size = max(math.sqrt(a) for a, c in faces)
    for i, ((a, c, r), (fa, fc)) in enumerate(zip(rows, faces)):
        if c is not None and (abs(a - fa) > 1e-3 * fa or max(abs(x - y) for x, y in zip(c, fc)) > 1e-5 * size):
            sys.exit('%s: polygon %d is not the OBJ face %d (area %g against %g)' % (what, i, i, a, fa))
    # Weighted by the reference's areas: what shows of each polygon (hrad cuts what a face lying flush on
    # it covers, lib/hrad/io/flush_faces.h; a peer reports the whole polygon).
    num = sum(a * (r - q) ** 2 for (_, c, r), (a, _, q) in zip(rows, reference))
    den = sum(a * q * q for a, c, q in reference)
    bias = sum(a * r for (_, c, r), (a, _, _) in zip(rows, reference)) / sum(a * q for a, c, q in reference) - 1
    return math.sqrt(num / den), bias


def timed(cmd, env=None, cwd=None):
    """Runs cmd pinned to core 0; returns its CPU seconds (user + system) and its output."""
    with open(os.devnull, 'rb') as null:
        p = subprocess.Popen(['taskset', '-c', '0'] + cmd, stdin=null, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, env=env, cwd=cwd)
        out = p.stdout.read()
        _, status, usage = os.wait4(p.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit('failed (%d): %s\n%s' % (os.waitstatus_to_exitcode(status), ' '.join(cmd), out.decode()[-2000:]))
    return usage.ru_utime + usage.ru_stime, out.decode(errors='replace')


def total_area(hrad, obj):
    return json.loads(subprocess.run([hrad, 'info', obj, '--json'], check=True, capture_output=True,
                                     text=True).stdout)['area']


def hrad_cmd(hrad, obj, setting, area, report, threads):
    """setting: None (the defaults), an aeps fraction of the total area, or (fraction or None, [options])."""
    aeps_fraction, options = setting if isinstance(setting, tuple) else (setting, [])
    cmd = [hrad, 'solve', obj, '--quiet', '--threads', str(threads), '--report', report] + options
    return cmd + (['--aeps', '%.9g' % (aeps_fraction * area)] if aeps_fraction is not None else [])


def run(args):
    peers = os.path.abspath(args.peers)
    hrad = os.path.abspath(args.hrad)
    splash, rpk = os.path.join(peers, 'splash', 'radiosity'), os.path.join(peers, 'rpkCpp', 'build', 'rpk')
    for exe in (hrad, splash, rpk):
        if not os.access(exe, os.X_OK):
            sys.exit('%s: not found or not executable (scripts/peers.py build ... first)' % exe)
    os.makedirs(args.work, exist_ok=True)
    scenes = args.scenes.split(',') if args.scenes else list(dict.fromkeys(s[0] for s in SETTINGS))
    settings = [s for s in SETTINGS if s[0] in scenes]
    started = time.time()
    results = []
    for scene in scenes:
        obj = os.path.join(SCENES, scene + '.obj')
        faces = read_obj_faces(obj)
        area = total_area(hrad, obj)
        ref_path = os.path.join(args.work, scene + '.reference.json')
        check_path = os.path.join(args.work, scene + '.reference_check.json')
        ruler_path = os.path.join(args.work, scene + '.ruler.csv')
        if not (args.reuse_references and os.path.exists(ref_path) and os.path.exists(check_path)):
            print('%s: reference (hrad %s, aeps total/%g and total/%g, all cores) ... %.0f s so far'
                  % (scene, ' '.join(REFERENCE_OPTIONS), 1 / REFERENCE_AEPS, 1 / (4 * REFERENCE_AEPS),
                     time.time() - started), file=sys.stderr)
            for fraction, path in ((REFERENCE_AEPS, ref_path), (4 * REFERENCE_AEPS, check_path)):
                subprocess.run(hrad_cmd(hrad, obj, (fraction, REFERENCE_OPTIONS), area, path, 0), check=True,
                               stdout=subprocess.DEVNULL)
        if not ((args.reuse_references or args.reuse_rulers) and os.path.exists(ruler_path)):
            print('%s: the Monte Carlo ruler (%d points per polygon, all cores) ... %.0f s so far'
                  % (scene, RULER_SAMPLES, time.time() - started), file=sys.stderr)
            subprocess.run([hrad, 'reference', obj, '--faces', '--samples', str(RULER_SAMPLES), '--quiet', '--out',
                            ruler_path], check=True, stdout=subprocess.DEVNULL)
        reference = read_answer(ref_path)
        check = l2_error(read_answer(check_path), reference, faces, check_path)
        ruler, ruler_noise = read_ruler(ruler_path, obj)
        ruler_diff = l2_error(reference, ruler, faces, ruler_path)
        runs = [s for s in settings if s[0] == scene]
        seconds = {i: [] for i in range(len(runs))}
        errors = {}
        for rep in range(args.repeats):
            for i, (_, program, label, setting) in enumerate(runs):
                out = os.path.join(args.work, '%s.%d' % (scene, i))
                env = dict(os.environ)
                if program == 'hrad':
                    out += '.json'
                    t, _ = timed(hrad_cmd(hrad, obj, setting, area, out, 1))
                elif program == 'SPLASH-2':
                    out += '.dump'
                    env['SPLASH_DUMP'] = out
                    t, _ = timed([splash, '-p', '1'] + SPLASH_SCENE[scene] + setting, env=env)
                else:
                    out += '.rdump'
                    env['RPK_DUMP'] = out
                    t, _ = timed([rpk, RPK_SCENE[scene]] + RPK + setting, env=env, cwd=os.path.join(peers, 'rpkCpp'))
                seconds[i].append(t)
                answer = read_answer(out)
                what = '%s %s %s' % (scene, program, label)
                errors[i] = errors_against(answer, reference, faces, what) + (
                    math.sqrt(max(0.0, l2_error(answer, ruler, faces, what) ** 2 - ruler_noise ** 2)),)
                done = sum(len(v) for v in seconds.values())
                total = len(runs) * args.repeats
                print('%s: %s %s: %.2f s CPU, L2 %.2f%% (%d/%d of this scene, %.0f s so far)' % (
                    scene, program, label, t, 100 * errors[i][0], done, total, time.time() - started), file=sys.stderr)
        # the time unit of each scene: hrad's default solve
        unit = statistics.median(seconds[next(i for i, s in enumerate(runs) if s[1] == 'hrad' and s[3] is None)])
        for i, (_, program, label, _) in enumerate(runs):
            med = statistics.median(seconds[i])
            results.append((scene, program, label, med, med / unit, errors[i], (check, ruler_diff, ruler_noise)))
    table = ['| scene | program, setting | CPU s (median of %d) | CPU / hrad defaults | L2 error per polygon | '
             'mean bias | L2 against the ruler |' % args.repeats, '| --- | --- | --- | --- | --- | --- | --- |']
    for scene, program, label, med, ratio, (err, bias, against_ruler), check in results:
        table.append('| %s | %s, %s | %.2f | %.2f | %.2f%% | %+.1f%% | %.2f%% |' % (
            scene, program, label, med, ratio, 100 * err, 100 * bias, 100 * against_ruler))
    table.append('')
    table.append('| scene | reference (hrad %s, aeps total/%g) against it at total/%g | against the Monte Carlo '
                 'ruler (%d points per polygon) | the ruler\'s own noise |' % (
                     ' '.join(REFERENCE_OPTIONS), 1 / REFERENCE_AEPS, 1 / (4 * REFERENCE_AEPS), RULER_SAMPLES))
    table.append('| --- | --- | --- | --- |')
    for scene, (check, ruler_diff, ruler_noise) in dict((r[0], r[6]) for r in results).items():
        table.append('| %s | %.2f%% | %.2f%% | %.2f%% |' % (scene, 100 * check, 100 * ruler_diff, 100 * ruler_noise))
    text = '\n'.join(table)
    open(os.path.join(args.work, 'table.md'), 'w').write(text + '\n')
    print(text)
    print('%.0f s in all; runs and the table in %s' % (time.time() - started, args.work), file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest='command', required=True)
    b = sub.add_parser('build', help='copy, add the dumps to and build both peers')
    b.add_argument('splash', help="splash2-posix's apps/radiosity folder")
    b.add_argument('rpk', help='an rpkCpp checkout')
    b.add_argument('peers', help='the build folder to create')
    b.add_argument('--jobs', type=int, default=2)
    r = sub.add_parser('run', help='run and score hrad and the peers')
    r.add_argument('peers', help="the folder 'build' made")
    r.add_argument('--hrad', default=os.path.join(ROOT, 'build', 'bin', 'hrad'))
    r.add_argument('--repeats', type=int, default=3)
    r.add_argument('--work', default='/tmp/hrad-peers')
    r.add_argument('--reuse-references', action='store_true',
                   help='keep the references and rulers an earlier run left in WORK (when hrad has not changed since)')
    r.add_argument('--reuse-rulers', action='store_true',
                   help="keep the Monte Carlo rulers an earlier run left in WORK (path tracing: they do not depend on "
                        "hrad's solvers)")
    r.add_argument('--scenes', help='comma-separated subset of ' + ','.join(dict.fromkeys(s[0] for s in SETTINGS)))
    args = parser.parse_args()
    build(args) if args.command == 'build' else run(args)


if __name__ == '__main__':
    main()
