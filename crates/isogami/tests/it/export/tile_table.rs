//! Tile tables: CSV parsed back field by field, JSON round trip, neighbours symmetric and
//! exactly the patch's joints, poses and angles consistent with the polygons.

use super::fixtures::{closed, open, DESIGNS};
use isogami::export::tile_table::{tile_csv, tile_table, TileTable, TILE_CSV_HEADER};

fn nums(field: &str) -> Vec<f64> {
    field
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

#[test]
fn csv_rows_hold_what_the_json_table_holds() {
    for (p, spec) in open().iter().zip(DESIGNS) {
        let table = tile_table(p);
        let csv = tile_csv(&table);
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some(TILE_CSV_HEADER));
        let columns = TILE_CSV_HEADER.split(',').count();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), p.tiles.len(), "{spec}");
        for (r, t) in rows.iter().zip(&table.tiles) {
            assert_eq!(r.len(), columns);
            assert_eq!(r[0].parse::<usize>().unwrap(), t.id);
            assert_eq!(
                [r[1].parse::<i32>().unwrap(), r[2].parse().unwrap()],
                t.cell
            );
            assert_eq!(r[3].parse::<usize>().unwrap(), t.tile);
            assert_eq!(r[4].parse::<f64>().unwrap(), t.pose.x);
            assert_eq!(r[6].parse::<f64>().unwrap(), t.pose.theta);
            let n: usize = r[8].parse().unwrap();
            let poly = nums(r[9]);
            assert_eq!(poly.len(), 2 * n);
            let flat: Vec<f64> = t.polygon_mm.iter().flatten().copied().collect();
            assert_eq!(poly, flat);
            let angles = nums(r[10]);
            let sum: f64 = angles.iter().sum();
            assert!(
                (sum - 180.0 * (n as f64 - 2.0)).abs() < 1e-6,
                "{spec}: {sum}"
            );
            let nb: Vec<usize> = nums(r[11]).iter().map(|&x| x as usize).collect();
            assert_eq!(nb, t.neighbours);
        }
        let json = serde_json::to_string(&table).unwrap();
        let back: TileTable = serde_json::from_str(&json).unwrap();
        assert_eq!(back, table);
        assert_eq!(back.unit, "mm");
    }
}

#[test]
fn neighbours_are_symmetric_and_are_the_joints() {
    for (p, spec) in closed().iter().zip(DESIGNS) {
        let table = tile_table(p);
        let mut from_table = Vec::new();
        for t in &table.tiles {
            for &n in &t.neighbours {
                let back = table.tiles[n]
                    .neighbours
                    .iter()
                    .filter(|&&m| m == t.id)
                    .count();
                let here = t.neighbours.iter().filter(|&&m| m == n).count();
                assert_eq!(back, here, "{spec}: {} and {n}", t.id);
                if t.id < n {
                    from_table.push((t.id, n));
                }
            }
        }
        let mut from_joints: Vec<_> = p
            .joints
            .iter()
            .map(|j| (j.a.min(j.b), j.a.max(j.b)))
            .collect();
        from_table.sort_unstable();
        from_joints.sort_unstable();
        assert_eq!(from_table, from_joints, "{spec}");
    }
}
