namespace HairSim.Measurement;

/// <summary>The points no other point beats on both cost and error (smaller is better on both axes).</summary>
public static class ParetoFront
{
    /// <summary>
    /// Indices of the non-dominated points, sorted by cost. A point is dominated when another has cost ≤ and
    /// error ≤ with at least one strictly smaller. Points with a non-finite cost or error are never on the front.
    /// Equal points are all kept.
    /// </summary>
    public static int[] Indices(IReadOnlyList<double> cost, IReadOnlyList<double> error)
    {
        if (cost.Count != error.Count) throw new ArgumentException("Cost and error lists differ in length.", nameof(error));
        var front = new List<int>();
        for (int i = 0; i < cost.Count; i++)
        {
            if (!double.IsFinite(cost[i]) || !double.IsFinite(error[i])) continue;
            bool dominated = false;
            for (int j = 0; j < cost.Count && !dominated; j++)
            {
                if (j == i || !double.IsFinite(cost[j]) || !double.IsFinite(error[j])) continue;
                dominated = cost[j] <= cost[i] && error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
            }
            if (!dominated) front.Add(i);
        }
        front.Sort((a, b) => cost[a] != cost[b] ? cost[a].CompareTo(cost[b]) : error[a].CompareTo(error[b]));
        return front.ToArray();
    }
}
