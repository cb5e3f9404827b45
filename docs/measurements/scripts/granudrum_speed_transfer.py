#!/usr/bin/env python3
"""Leave one speed out on the GranuDrum MCC photos: calibrate on one speed, predict the other.

usage: granudrum_speed_transfer.py DEMFIT OUT [--study cases/granudrum_calibration_quick.json]
                                   [--extra NAME:LOWER:UPPER:INITIAL ...] [--fills 1,2,3] [--jobs 2]

For each direction (15 -> 45 rpm, 45 -> 15 rpm) the study is cut to the one experiment it is
calibrated on, `demfit identify` fits it, and the answer's variables are run at the other speed
(the study's own overrides for that speed) on each fill seed; the predicted free surface is
compared with the other photo (`demfit target compare`, RMS gap in mm). The baseline is the
photo lookup: the calibration speed's own photo profile taken as the prediction of the other.
--extra adds a variable to the calibration (e.g. cohesion_energy_density:0:100000:0 for SJKR
cohesion [J/m^3], restitution:0.05:0.95:0.3 for the released restitution), so a candidate effect's
transfer is measured beside the base model's. --set-answer NAME=VALUE replaces one of the answer's
values before the runs at both speeds (e.g. cohesion_energy_density=0: the same calibration with the
effect switched off, to see whether the effect or the rest of the answer carries the prediction).
A calibration already in OUT is resumed (`identify --resume`), not repeated.
Prints one table; every file stays in OUT. Runs only demfit (argument vectors, no shell).
"""
import argparse, copy, json, os, re, statistics, subprocess, sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', '..'))


def run(args, **kw):
    done = subprocess.run(args, capture_output=True, text=True, **kw)
    if done.returncode != 0:
        sys.exit('failed: ' + ' '.join(args) + '\n' + done.stderr[-2000:])
    return done.stdout


def rms_gap(demfit, simulated, measured):
    out = run([demfit, 'target', 'compare', simulated, measured])
    m = re.search(r'RMS gap ([0-9.eE+-]+) mm', out)
    if not m:
        sys.exit('no RMS in: ' + out)
    return float(m.group(1))


def deep_merge(base, extra):
    out = copy.deepcopy(base)
    for k, v in extra.items():
        out[k] = deep_merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument('demfit')
    p.add_argument('out')
    p.add_argument('--study', default=os.path.join(ROOT, 'cases', 'granudrum_calibration_quick.json'))
    p.add_argument('--extra', action='append', default=[])
    p.add_argument('--fills', default='1,2,3')
    p.add_argument('--jobs', default='2')
    p.add_argument('--set-answer', action='append', default=[])
    a = p.parse_args()
    demfit, out = os.path.abspath(a.demfit), os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    study_path = os.path.abspath(a.study)
    study_dir = os.path.dirname(study_path)
    study = json.load(open(study_path))
    experiments = {e['name']: e for e in study['experiments']}
    photos = {}
    for name, e in experiments.items():
        t = e['targets'][0]
        folder = os.path.join(out, 'photo_' + name)
        run([demfit, 'target', 'from-image', os.path.join(study_dir, t['image']), '--diameter',
             str(t['image_diameter']) + 'm', '--margin', str(t.get('image_margin', 0.1)), '--points',
             str(t.get('image_points', 41)), '--out', folder])
        photos[name] = os.path.join(folder, 'free_surface.csv')
    fills = [int(f) for f in a.fills.split(',')]
    rows = []
    for fit_on, predict in (('rpm15', 'rpm45'), ('rpm45', 'rpm15')):
        one = copy.deepcopy(study)
        extras = [e.split(':') for e in a.extra]
        one['name'] = study['name'] + '_' + fit_on + ''.join('_' + e[0] for e in extras)
        one['experiments'] = [copy.deepcopy(experiments[fit_on])]
        for t in one['experiments'][0]['targets']:
            t['image'] = os.path.join(study_dir, t['image'])
        one['experiments'][0]['model']['case'] = os.path.join(study_dir, one['experiments'][0]['model']['case'])
        for name, lower, upper, initial in extras:
            one['variables'].append({'name': name, 'lower': float(lower), 'upper': float(upper),
                                     'initial': float(initial)})
        study_file = os.path.join(out, one['name'] + '.json')
        json.dump(one, open(study_file, 'w'), indent=2)
        fit_dir = os.path.join(out, 'fit_' + one['name'])
        resume = ['--resume'] if os.path.isdir(fit_dir) else []
        run([demfit, 'identify', study_file, '--out', fit_dir, '--jobs', a.jobs, '--no-plots'] + resume)
        best = json.load(open(os.path.join(fit_dir, 'best_parameters.json')))
        values = {k: v['value'] for k, v in best['variables'].items()}
        for assignment in a.set_answer:
            name, value = assignment.split('=')
            if name not in values:
                sys.exit('--set-answer: %s is not a variable of the answer (%s)' % (name, ', '.join(values)))
            values[name] = float(value)
        tag = ''.join('_' + x.replace('=', '') for x in a.set_answer)
        target = experiments[predict]
        case = deep_merge(json.load(open(os.path.join(study_dir, target['model']['case']))),
                          target['model'].get('overrides', {}))
        fit_errors, errors = [], []
        for fill in fills:
            for speed, model in ((fit_on, experiments[fit_on]['model']), (predict, target['model'])):
                c = deep_merge(json.load(open(os.path.join(study_dir, model['case']))), model.get('overrides', {}))
                c['drum']['fill_seed'] = fill
                case_file = os.path.join(out, 'case_%s%s_%s_fill%d.json' % (one['name'], tag, speed, fill))
                json.dump(c, open(case_file, 'w'), indent=2)
                sim_dir = os.path.join(out, 'sim_%s%s_%s_fill%d' % (one['name'], tag, speed, fill))
                args = [demfit, 'simulate', case_file, '--out', sim_dir, '--threads', a.jobs]
                for k, v in values.items():
                    args += ['--set', '%s=%r' % (k, v)]
                run(args)
                gap = rms_gap(demfit, os.path.join(sim_dir, 'free_surface_image.csv'), photos[speed])
                (fit_errors if speed == fit_on else errors).append(gap)
        lookup = rms_gap(demfit, photos[fit_on], photos[predict])
        rows.append((fit_on, predict, values, fit_errors, errors, lookup))
    print('| calibrated on | predicts | answer | RMS at the calibration speed (mm, fills %s) | '
          'RMS predicted (mm) | photo lookup (mm) |' % a.fills)
    print('|---|---|---|---|---|---|')
    for fit_on, predict, values, fit_errors, errors, lookup in rows:
        def ms(x):
            return '%.2f ± %.2f' % (statistics.mean(x), statistics.stdev(x) if len(x) > 1 else 0.0)
        answer = ', '.join('%s %.4g' % kv for kv in values.items())
        print('| %s | %s | %s | %s | %s | %.2f |' % (fit_on, predict, answer, ms(fit_errors), ms(errors), lookup))


if __name__ == '__main__':
    main()
